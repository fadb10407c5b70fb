#!/usr/bin/env python3
"""Benchmark of the exact rolling solver (&rolling), one thread.

  scripts/bench/bench_rolling.py [--kcreep build/kcreep] [--shared ../shared] [--repeat 3] [--doc docs/rolling.md]

Runs, with OMP_NUM_THREADS=1 and holding /tmp/kcreep-bench.lock (so that no
other benchmark runs at the same time on the shared machine):
  - the 24-point curves of CONTACT's four slip patches (../shared/contact-slip,
    CONTACT's grid, mask and pressure), beside CONTACT's own wall-clock time of
    the same 24 cases (the "Total" timer of its .out);
  - one point (xi = 2e-3, about half the patch in slip; and the combined
    (-5e-4, 2e-3, -1e-3)) on the Hertzian circle R = 5 mm on 100 x 100 and
    200 x 200 cells.
Times are those kcreep prints for the rolling stage (operator set-up and
Newton solves; the full-adhesion coefficients solved before are not included),
best of --repeat runs; Newton steps and operator products per point as printed.
Writes the table into the section `bench_rolling` of --doc (replaced on rerun)
and prints it. Standard library only."""
import argparse
import fcntl
import os
import re
import subprocess
import sys
import tempfile


def main():
    here = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0], formatter_class=argparse.RawDescriptionHelpFormatter,
                                 epilog=__doc__)
    ap.add_argument('--kcreep', default=os.path.join(here, 'build', 'kcreep'))
    ap.add_argument('--shared', default=os.path.join(here, '..', 'shared'))
    ap.add_argument('--repeat', type=int, default=3)
    ap.add_argument('--doc', default=os.path.join(here, 'docs', 'rolling.md'))
    args = ap.parse_args()
    sys.path.insert(0, os.path.join(here, 'python'))
    from kcreep.docsection import replace_section
    import csv

    env = dict(os.environ, OMP_NUM_THREADS='1')
    slip = os.path.join(args.shared, 'contact-slip')
    summary = list(csv.DictReader(open(os.path.join(slip, 'slip_summary.csv'))))
    rows = []
    with open('/tmp/kcreep-bench.lock', 'w') as lock, tempfile.TemporaryDirectory() as tmp:
        fcntl.flock(lock, fcntl.LOCK_EX)

        def run(name, text):
            path = os.path.join(tmp, name + '.nml')
            with open(path, 'w') as f:
                f.write(text)
            best = None
            for _ in range(args.repeat):
                r = subprocess.run([args.kcreep, path], cwd=tmp, env=env, capture_output=True, text=True)
                if r.returncode != 0:
                    sys.exit(f'bench_rolling: kcreep failed on {name}: {r.stderr.strip()}')
                m = re.search(r'exact rolling: (\d+) creepage points.*?,\s+([0-9.]+) s(?: on \d+ thread\(s\))?; '
                              r'Newton steps per point\s+([0-9.]+), '
                              r'operator products per point\s+([0-9.]+)', r.stdout)
                res = re.search(r'largest residual max\|F\|/max\(mu pn\)\s+(\S+);', r.stdout).group(1)
                cells = re.search(r'grid (\d+) x (\d+), (\d+) cells', r.stdout).group(3)
                t = float(m.group(2))
                if best is None or t < best[0]:
                    best = (t, m.group(1), m.group(3), m.group(4), res, cells)
            return best

        for patch in ('circle', 'ellipse_ab0p5', 'kidney', 'twin'):
            cases = [c for c in summary if c['patch'] == patch]
            creep = ',  '.join(f"{c['xi']} {c['eta']} {c['phi']}" for c in cases)
            out = os.path.join(slip, patch, f'{patch}_mu0p3.out')
            t, npts, newton, products, res, cells = run(patch, f"&patch shape = 'contact', contact_file = '{out}' /\n"
                                                        f"&rolling mu = 0.3, creepages = {creep} /\n")
            text = open(out).read()
            contact = float(re.search(r'\|Total\s+\|\s+\d+\s+\|\s+[0-9.]+\s+\|\s+[0-9.]+\s+\|\s+([0-9.]+)', text).group(1))
            rows.append(f'| {patch}, 24-point curve | {cells} | {t:.3f} | {float(newton):.1f} | {float(products):.0f} | '
                        f'{res} | {contact:.1f} ({contact / t:.0f}x) |')
        for m in (100, 200):
            for creep in ('2e-3 0 0', '-5e-4 2e-3 -1e-3'):
                t, npts, newton, products, res, cells = run(
                    f'circle{m}', f"&patch shape = 'ellipse', semi_a = 5, semi_b = 5, mx = {m}, my = {m} /\n"
                    "&material g = 82000, nu = 0.25 /\n&solver target_error = 0 /\n"
                    f"&rolling mu = 0.3, fn = 82000, creepages = {creep} /\n")
                rows.append(f'| circle R = 5, {m} x {m}, one point ({creep}) | {cells} | {t:.3f} | {float(newton):.0f} | '
                            f'{float(products):.0f} | {res} | - |')
    table = ('Measured by `scripts/bench/bench_rolling.py` (one thread, best of '
             f'{args.repeat}; rolling stage only):\n\n'
             '| case | cells | seconds | Newton steps per point | operator products per point | largest residual | '
             'CONTACT (GDsteady) seconds (ratio) |\n|---|---|---|---|---|---|---|\n' + '\n'.join(rows) + '\n')
    print(table)
    replace_section(args.doc, 'bench_rolling', table)


if __name__ == '__main__':
    main()
