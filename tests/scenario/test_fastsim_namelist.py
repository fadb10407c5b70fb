"""&fastsim through the program: the creep table, its columns and defaults, the
checks of issue-level behaviour on kcreep's own numbers, the maps, the pressure
sources and bad input.
  - no &fastsim group: no creep table is written;
  - small creepage: fx = -f11 xi, fy = -f22 eta, fy = -f23 phi of the coefficient table
    (the exact L reproduce the coefficients to round-off: FASTSIM in full adhesion is exact
    for the rigid slip of any patch, measured 1e-15 relative; allowed 1e-9);
  - large creepage: |F| = mu Fn, adhesion 0; with the default rule 'aligned' F points along the
    creepage (70, 70, 0) (measured: |F| short of mu Fn by 5e-10 relative and 4e-6 rad off, the
    elastic part of the cells' slip; allowed 1e-8 and 1e-5 rad; the separate rule is 0.05 rad off);
  - the creep table's default name <input>.creep in the working folder; creep_file moves it;
  - maps: one block per point and source, states 1/2, traction bound |p| <= mu pn;
  - pressure 'contact' from CONTACT's element file (ellipse_a6_b4_slip, mu = 0.3): FX of case 1
    within 2.5 % of mu Fn of CONTACT's (measured 1.9 %);
  - pressure 'normal' (shape = 'gap'): fn = the prescribed normal force (the normal solve's
    tolerance: 1e-6), slopes exact;
  - pressure file on the mask's grid: fn = sum p dA; a bare mask warns that its pressure is a model;
  - bad input: one error line naming &fastsim and the variable, exit 2, nothing written.
usage: test_fastsim_namelist.py KCREEP SAMPLES_DIR"""
import math
import os
import sys
import kctest as kc

folder = kc.setup()
samples = os.path.abspath(sys.argv[2])


def creep_rows(path):
    cols, rows = None, []
    for line in open(path):
        if line.startswith('#'):
            cols = line[1:].split()
            continue
        rows.append({c: (v if c == 'source' else float(v)) for c, v in zip(cols, line.split())})
    return cols, rows


# 1. absent group: nothing of FASTSIM
kc.run("&patch mx = 20, my = 20 /\n", folder, 'plain')
kc.check(not os.path.exists(os.path.join(folder, 'plain.creep')), 'no &fastsim: no creep table')

# 2. an ellipse with Hertz pressure: slopes, saturation, columns, sources
text = ("&patch semi_a = 1.5, semi_b = 1, mx = 30, my = 30 /\n&material g = 2, nu = 0.3 /\n"
        "&fastsim mu = 0.25, fn = 3, flexibility = 'exact ellipse-box user', l1 = 0.5, l2 = 0.6, l3 = 0.4,\n"
        "  creepages = 1e-9 0 0, 0 1e-9 0, 0 0 1e-9, 100 0 0, 70 70 0 /\n")
code, out, err, table = kc.run(text, folder, 'ell')
row = table[0]
cols, rows = creep_rows(os.path.join(folder, 'ell.creep'))
kc.check(cols[:9] == 'xi eta phi fx fy mz fn adhesion source'.split() and cols[9:11] == ['fx_mufn', 'fy_mufn'],
         f'creep table columns {cols}')
kc.check(len(rows) == 5 * 3, f'{len(rows)} rows: 5 points x 3 sources')
kc.check([r['source'] for r in rows[:3]] == ['exact', 'ellipse-box', 'user'], 'sources in order')
ex = [r for r in rows if r['source'] == 'exact']
kc.close(-ex[0]['fx'] / 1e-9, row['f11'], 1e-9, 'small xi: fx = -f11 xi')
kc.close(-ex[1]['fy'] / 1e-9, row['f22'], 1e-9, 'small eta: fy = -f22 eta')
kc.close(-ex[2]['fy'] / 1e-9, row['f23'], 1e-9, 'small phi: fy = -f23 phi')
kc.check(all(r['adhesion'] == 1 for r in ex[:3]), 'small creepage: all in adhesion')
kc.close(ex[0]['fn'], 3.0, 1e-12, 'fn of the Hertz pressure')
kc.close(-ex[3]['fx_mufn'], 1.0, 1e-12, 'large xi: Fx = -mu Fn')
kc.check(ex[3]['adhesion'] == 0, 'large xi: full slip')
kc.close(math.hypot(ex[4]['fx_mufn'], ex[4]['fy_mufn']), 1.0, 1e-8, 'large (xi, eta): |F| = mu Fn')
turn = abs(math.atan2(ex[4]['fy_mufn'], ex[4]['fx_mufn']) + 3 * math.pi / 4)
kc.check(turn < 1e-5, f'large (xi, eta), default rule aligned: F along -(xi, eta) ({turn:.1e} rad off)')
kc.check('FASTSIM: 5 creepage points x 3 flexibility source(s)' in out, 'summary names the FASTSIM run')
kc.check('largest |F - F(exact L)|' in out, 'summary: force difference of the other sources')

# 3. creep_file, a sweep, the maps
text = ("&patch semi_a = 1, semi_b = 1, mx = 16, my = 16 /\n"
        "&fastsim mu = 0.3, sweep_direction = 0 1 0, sweep_from = 1e-3, sweep_to = 1, sweep_points = 4,\n"
        "  sweep_spacing = 'log', maps = .true. /\n&output creep_file = 'sub.creep' /\n")
kc.run(text, folder, 'sweep')
cols, rows = creep_rows(os.path.join(folder, 'sub.creep'))
kc.close(rows[-1]['eta'], 1.0, 1e-12, 'log sweep ends at sweep_to')
kc.close(rows[1]['eta'], 1e-2, 1e-12, 'log sweep: geometric steps')
mp = os.path.join(folder, 'sweep.creepmap')
kc.check(os.path.exists(mp), 'maps = .true.: <input>.creepmap')
blocks = open(mp).read().split('\n\n\n')
kc.check(len(blocks) == 4, f'{len(blocks)} map blocks (one per point)')
cells = [l.split() for l in blocks[2].splitlines() if l and not l.startswith('#')]
# (printed with 9 digits: allowed 1e-7 relative)
kc.check(all(math.hypot(float(c[5]), float(c[6])) <= 0.3 * float(c[4]) * (1 + 1e-7) for c in cells),
         'maps: |p| <= mu pn on every cell')
kc.check({c[7] for c in cells} == {'1', '2'}, 'maps: partial slip point has adhesion and slip cells')

# 4. CONTACT pressure: the slip sample
out_path = os.path.join(samples, 'ellipse_a6_b4_slip.out')
text = (f"&patch shape = 'contact', contact_file = '{out_path}', contact_case = 1 /\n"
        "&fastsim mu = 0.3, creepages = 1e-3 0 0 /\n")
code, out, err, table = kc.run(text, folder, 'cslip')
cols, rows = creep_rows(os.path.join(folder, 'cslip.creep'))
kc.check(abs(rows[0]['fx_mufn'] - (-0.3411)) < 0.025, f"CONTACT pressure: fx/(mu fn) {rows[0]['fx_mufn']:.4f} vs CONTACT -0.3411")
kc.close(rows[0]['fn'], 8.2e4, 1e-3, 'CONTACT pressure: fn = sum PN dA = FN')

# 4b. the normal solve's pressure (shape = 'gap'): fn is the prescribed normal force, slopes exact
text = ("&patch shape = 'gap' /\n&normal rx = 50, ry = 30, normal_force = 10, cells_across = 30 /\n"
        "&solver scheme = 'backward' /\n&fastsim mu = 0.3, creepages = 1e-9 0 0, 0 0 1e-9 /\n")
code, out, err, table = kc.run(text, folder, 'gap')
cols, rows = creep_rows(os.path.join(folder, 'gap.creep'))
kc.close(rows[0]['fn'], 10.0, 1e-6, 'normal pressure: fn = normal_force')
kc.close(-rows[0]['fx'] / 1e-9, table[0]['f11'], 1e-9, 'normal pressure: fx = -f11 xi')
kc.close(-rows[1]['fy'] / 1e-9, table[0]['f23'], 1e-9, 'normal pressure: fy = -f23 phi')
kc.check('pressure normal' in out, 'summary names the normal pressure')

# 5. pressure file = the model written out
mask = "6 4 0.5 0.5 -1.25 -0.75\n.####.\n######\n######\n.####.\n"
p = [[0, 1, 2, 2, 1, 0], [1, 2, 3, 3, 2, 1], [1, 2, 3, 3, 2, 1], [0, 1, 2, 2, 1, 0]]
pfile = "6 4 0.5 0.5 -1.25 -0.75\n" + "\n".join(" ".join(str(v) for v in r) for r in p) + "\n"
text = ("&patch shape = 'mask', mask_file = 'm.mask' /\n"
        "&fastsim mu = 0.3, pressure_input_file = 'p.txt', creepages = 1 0 0 /\n")
code, out, err, table = kc.run(text, folder, 'pf', files={'m.mask': mask, 'p.txt': pfile})
cols, rows = creep_rows(os.path.join(folder, 'pf.creep'))
kc.close(rows[0]['fn'], sum(map(sum, p)) * 0.25, 1e-12, 'pressure file: fn = sum p dA')
text = "&patch shape = 'mask', mask_file = 'm.mask' /\n&fastsim mu = 0.3, creepages = 1e-3 0 0 /\n"
code, out, err, table = kc.run(text, folder, 'model')
kc.check('parabolic strip MODEL' in err, 'bare mask: warning that the pressure is a model')

# 6. bad input
bad = [("&fastsim creepages = 1 0 0 /", "mu is required"),
       ("&fastsim mu = -1, creepages = 1 0 0 /", "mu = -1"),
       ("&fastsim mu = 0.3, creepages = 1 0 0 2 /", "creepages: 4 numbers"),
       ("&fastsim mu = 0.3 /", "no creepage"),
       ("&fastsim mu = 0.3, creepages = 1 0 0, flexibility = 'user' /", "needs l1, l2, l3"),
       ("&fastsim mu = 0.3, creepages = 1 0 0, flexibility = 'magic' /", "unknown source 'magic'"),
       ("&fastsim mu = 0.3, creepages = 1 0 0, rule = 'average' /", "rule = 'average'"),
       ("&fastsim mu = 0.3, creepages = 1 0 0, pressure = 'contact' /", "pressure = 'contact' needs"),
       ("&fastsim mu = 0.3, sweep_direction = 1 0 0, sweep_points = 1 /", "sweep_points = 1"),
       ("&fastsim mu = 0.3, sweep_direction = 1 0 0, sweep_points = 3, sweep_spacing = 'log' /", "needs 0 < value"),
       ("&fastsim mu = 0.3, creepages = 1 0 0, pressure = 'file', pressure_input_file = 'nope.txt' /", "nope.txt")]
for k, (group, expect) in enumerate(bad):
    name = f'bad{k}'
    code, out, err, table = kc.run("&patch mx = 10, my = 10 /\n" + group + "\n", folder, name, expect_ok=False)
    lines = err.strip().splitlines()
    kc.check(code == 2 and len(lines) == 1 and expect in lines[0] and
             ('&fastsim' in lines[0] or 'pressure_input_file' in lines[0]),
             f'bad input {group!r}: exit {code}, {lines}')
    kc.check(not os.path.exists(os.path.join(folder, name + '.creep')) and
             not os.path.exists(os.path.join(folder, name + '.tab')), f'{name}: nothing written')
wrong = "6 4 0.5 0.5 -1.0 -0.75\n" + "\n".join(" ".join(str(v) for v in r) for r in p) + "\n"
code, out, err, table = kc.run("&patch shape = 'mask', mask_file = 'm.mask' /\n"
                               "&fastsim mu = 0.3, pressure_input_file = 'w.txt', creepages = 1 0 0 /\n",
                               folder, 'wrong', expect_ok=False, files={'w.txt': wrong})
kc.check(code == 2 and "is not the patch's grid" in err and not os.path.exists(os.path.join(folder, 'wrong.creep')),
         f'pressure file on another grid: {err.strip()}')
kc.finish()
