"""&rolling through the program: the rolling table and its columns, the maps, sweeps,
the summary beside &fastsim, --batch, and bad input (mu <= 0, no creepage, a pressure
that is missing or does not fit the patch, the collocation scheme), each a one-line error
with exit status 2 that names the group and variable.
Small creepage: on the Hertzian ellipse 6 x 4 (40 x 30 cells) at xi = 1e-7, mu = 0.3, a few
trailing cells slip; Fx = -f11 xi within 2e-4 (measured 5e-5 relative), and pure spin at
phi = 1e-8 gives Fy = -f23 phi and Mz = -f33 phi to the same order (the rolling forces
tend to the table's coefficients of the same grid)."""
import os
import subprocess
import kctest as kc

tmp = kc.setup()
ell = "&patch shape = 'ellipse', semi_a = 6, semi_b = 4, mx = 40, my = 30 /\n&material g = 82000, nu = 0.28 /\n" \
      "&solver scheme = 'backward', target_error = 0 /\n"


def rows(path):
    return [[float(v) for v in l.split()] for l in open(path) if l.strip() and not l.startswith('#')]


# a good run: columns, small creepage, maps, sweep
rc, out, err, tab = kc.run(ell + "&rolling mu = 0.3, fn = 5e4, creepages = 1e-7 0 0,  0 0 1e-8,  2e-3 0 0, maps = .true.,\n"
                           "  sweep_direction = 0 1 0, sweep_from = 1e-4, sweep_to = 4e-3, sweep_points = 5 /\n", tmp, "good")
header = [l for l in open(os.path.join(tmp, 'good.roll')) if l.startswith('# xi')][0].split()[1:]
kc.check(header == 'xi eta phi fx fy mz fn adhesion fx_mufn fy_mufn newton residual'.split(),
         f'rolling table columns: {" ".join(header)}')
r = rows(os.path.join(tmp, 'good.roll'))
kc.check(len(r) == 8, f'{len(r)} rows: 3 listed + 5 swept')
t = tab[0]
kc.close(r[0][3], -t['f11'] * 1e-7, 2e-4, 'xi = 1e-7: Fx = -f11 xi')
kc.close(r[1][4], -t['f23'] * 1e-8, 2e-4, 'phi = 1e-8: Fy = -f23 phi')
kc.close(r[1][5], -t['f33'] * 1e-8, 2e-4, 'phi = 1e-8: Mz = -f33 phi')
kc.check(all(row[11] <= 1e-7 for row in r), 'residual column <= the default tolerance 1e-7')
kc.check(r[2][3] < 0 and 0 < r[2][7] < 1 and abs(r[2][8]) < 1, f'xi = 2e-3: partial slip (adhesion {r[2][7]})')
kc.check(all(abs(row[9]) <= 1 + 1e-12 and abs(row[8]) <= 1 + 1e-12 for row in r), '|F| <= mu Fn')
kc.check('exact rolling: 8 creepage points' in out and 'rolling table: good.roll' in out, 'summary lines')
maps = [l.split() for l in open(os.path.join(tmp, 'good.rollmap')) if l.strip() and not l.startswith('#')]
kc.check(len(maps) == 8 * int(t['n']), f'{len(maps)} map lines: 8 blocks of {int(t["n"])} cells')
kc.check(all(float(m[5])**2 + float(m[6])**2 <= (0.3 * float(m[4]))**2 * (1 + 1e-7) for m in maps),
         'maps: |p| <= mu pn in every cell (to the 9 printed digits)')
kc.check({m[7] for m in maps} == {'1', '2'}, 'maps: states 1 (adhesion) and 2 (slip)')

# both groups: FASTSIM's distance from the exact forces per source
rc, out, err, tab = kc.run(ell + "&rolling mu = 0.3, fn = 5e4, creepages = 1e-3 0 0,  -5e-4 2e-3 -1e-3 /\n"
                           "&fastsim mu = 0.3, fn = 5e4, creepages = 1e-3 0 0, flexibility = 'exact ellipse' /\n",
                           tmp, "both")
lines = [l for l in out.splitlines() if 'FASTSIM' in l and 'against exact' in l]
kc.check(len(lines) == 3 and all('% of mu Fn' in l for l in lines), f'summary: FASTSIM against exact per source ({len(lines)})')
fast = [l for l in out.splitlines() if 'fast model against exact' in l]
kc.check(len(fast) == 1 and float(fast[0].split('=')[1].split('%')[0]) < 2,
         f'summary: the fast force model against exact, within 2 % of mu Fn: {fast}')

# --batch runs &rolling per case
with open(os.path.join(tmp, 'b1.nml'), 'w') as f:
    f.write(ell + "&rolling mu = 0.3, creepages = 1e-3 0 0 /\n")
with open(os.path.join(tmp, 'cases.list'), 'w') as f:
    f.write('b1.nml\n')
p = subprocess.run([kc.KCREEP, '--batch', 'cases.list'], cwd=tmp, capture_output=True, text=True)
kc.check(p.returncode == 0 and len(rows(os.path.join(tmp, 'b1.roll'))) == 1, f'--batch writes b1.roll (exit {p.returncode})')

# bad input
bad = [
    ("&rolling mu = 0, creepages = 1e-3 0 0 /", "&rolling mu = 0"),
    ("&rolling mu = -0.3, creepages = 1e-3 0 0 /", "allowed: 0 < mu <= 1000"),
    ("&rolling creepages = 1e-3 0 0 /", "&rolling mu is required"),
    ("&rolling mu = 0.3 /", "&rolling no creepage"),
    ("&rolling mu = 0.3, creepages = 1e-3 0 /", "a multiple of 3"),
    ("&rolling mu = 0.3, creepages = 1e-3 0 0, pressure = 'file' /", "needs pressure_input_file"),
    ("&rolling mu = 0.3, creepages = 1e-3 0 0, pressure = 'contact' /", "pressure = 'contact' needs"),
    ("&rolling mu = 0.3, creepages = 1e-3 0 0, pressure = 'normal' /", "pressure = 'normal' needs"),
    ("&rolling mu = 0.3, creepages = 1e-3 0 0, tolerance = 0 /", "tolerance = 0"),
    ("&rolling mu = 0.3, creepages = 1e-3 0 0, fn = -1 /", "fn = -1"),
]
for k, (group, words) in enumerate(bad):
    rc, out, err, _ = kc.run(ell + group + "\n", tmp, f"bad{k}", expect_ok=False)
    kc.check(rc == 2 and words in err and len(err.strip().splitlines()) == 1 and f"bad{k}.nml" in err,
             f'{group}: exit {rc}, one line naming it: {err.strip()[:160]}')
mask = "&patch shape = 'mask', mask_rows = '0110', '1111', '0110', dx = 1, dy = 1 /\n&solver target_error = 0 /\n"
rc, out, err, _ = kc.run(mask + "&rolling mu = 0.3, creepages = 1e-3 0 0, pressure = 'hertz' /\n", tmp, "badmask",
                         expect_ok=False)
kc.check(rc == 2 and "pressure = 'hertz' needs" in err, f'hertz pressure on a mask: {err.strip()[:160]}')
rc, out, err, _ = kc.run(ell.replace("'backward'", "'collocation'") + "&rolling mu = 0.3, creepages = 1e-3 0 0 /\n",
                         tmp, "badscheme", expect_ok=False)
kc.check(rc == 2 and "scheme = 'backward'" in err, f'collocation refused: {err.strip()[:160]}')
kc.check(not os.path.exists(os.path.join(tmp, 'bad0.roll')), 'no rolling table after an error')
kc.finish()
