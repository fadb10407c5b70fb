#!/usr/bin/env python3
"""FASTSIM timing section of docs/performance.md (standard library only).
Runs kcreep_fastsim_bench (the creep curve alone: 100 creepage points, unit circle with Hertz
pressure, best and median of 21 repetitions) on 100 x 100 and 200 x 200 grids, and kcreep end to
end on a 100 x 100 circle with a 100-point &fastsim sweep (the exact coefficients solved once),
then replaces the section between the fastsim-bench markers of docs/performance.md (appends it when
missing). scripts/bench/bench.sh calls it at its end; alone:
  flock /tmp/kcreep-bench.lock python3 scripts/bench/bench_fastsim.py build .
  scripts/bench/bench_fastsim.py --help    this text
"""
import os
import re
import subprocess
import sys
import tempfile
if any(a in ("-h", "--help") for a in sys.argv[1:]):
    print(__doc__.strip())
    sys.exit(0)

build, root = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
bench = os.path.join(build, 'kcreep_fastsim_bench')
kcreep = os.path.join(build, 'kcreep')
lines = ['## FASTSIM creep curves', '',
         'Written by `scripts/bench/bench_fastsim.py` (also run by `scripts/bench/bench.sh`). The curve alone '
         '(`kcreep_fastsim_bench N POINTS`: unit circle, Hertz pressure, Kalker\'s L, combined creepages '
         '(0.3, 0.2, 0.1) s for s from 1e-3 to 1 (full adhesion to full slip), best and median of 21 runs):', '',
         '| grid | cells | points | rule | best [s] | median [s] | per cell and point [s] |', '|---|---|---|---|---|---|---|']
for n in (100, 200):
    out = subprocess.run([bench, str(n), '100'], capture_output=True, text=True, check=True).stdout
    for line in out.splitlines():
        m = re.search(r'rule (\w+): best +([0-9.]+) s, median +([0-9.]+) s, per cell and point +([0-9.E+-]+)', line)
        cells = sum(1 for iy in range(n) for ix in range(n)
                    if ((ix + 0.5) * 2 / n - 1) ** 2 + ((iy + 0.5) * 2 / n - 1) ** 2 <= 1)
        lines.append(f'| {n} x {n} | {cells} | 100 | {m.group(1)} | {m.group(2)} | {m.group(3)} | {float(m.group(4)):.2e} |')
with tempfile.TemporaryDirectory() as tmp:
    with open(os.path.join(tmp, 'c.nml'), 'w') as f:
        f.write("&patch semi_a = 1, semi_b = 1, mx = 100, my = 100 /\n&solver scheme = 'backward' /\n"
                "&fastsim mu = 0.3, sweep_direction = 0.3 0.2 0.1, sweep_from = 1e-3, sweep_to = 1,\n"
                "  sweep_points = 100, sweep_spacing = 'log' /\n")
    out = subprocess.run([kcreep, 'c.nml'], cwd=tmp, capture_output=True, text=True, check=True).stdout
    t_total = float(re.search(r'time assemble factor solve total \[s\]: +\S+ +\S+ +\S+ +(\S+)', out).group(1))
    t_fast = float(re.search(r'FASTSIM: .* ([0-9.]+) s$', out, re.M).group(1))
lines += ['', f'End to end (`kcreep` on a 100 x 100 circle, backward scheme, `&fastsim` with a 100-point sweep): '
          f'exact coefficients {t_total:.3f} s (solved once), the 100-point curve {t_fast:.4f} s '
          f'(target: under 0.1 s).', '']
path = os.path.join(root, 'docs', 'performance.md')
text = open(path).read() if os.path.exists(path) else ''
# only the section between its markers is replaced; the rest of the file is left alone
section = '<!-- fastsim-bench:begin -->\n' + '\n'.join(lines).rstrip('\n') + '\n<!-- fastsim-bench:end -->'
pattern = re.compile(r'<!-- fastsim-bench:begin -->.*?<!-- fastsim-bench:end -->', re.S)
if pattern.search(text):
    text = pattern.sub(lambda m: section, text)
else:
    text = text.rstrip('\n') + '\n\n' + section + '\n'
with open(path, 'w') as f:
    f.write(text)
print('\n'.join(lines))
