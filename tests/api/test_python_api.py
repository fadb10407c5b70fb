"""The Python package (python/kcreep) on the build tree's libkcreep:
solve_ellipse and solve_mask with numpy arrays, errors as KcreepError with
kcreep's message, tractions, operator-table reuse on one Solver, the
table module, and `pip install ./python` into a scratch folder.

usage: /usr/bin/python3 test_python_api.py KCREEP SOURCE_DIR   (needs numpy)
"""
import glob
import os
import shutil
import subprocess
import sys

import kctest as kc

folder = kc.setup()
source_dir = os.path.abspath(sys.argv[2])
sys.path.insert(0, os.path.join(source_dir, "python"))
import numpy as np  # noqa: E402
import kcreep  # noqa: E402

# the package finds build/libkcreep.so of the source tree without any setting
os.environ.pop("KCREEP_LIBRARY", None)
r = kcreep.solve_ellipse(1.0, 1.0, nu=0.25, g=1.0, mx=30, my=30, scheme="backward")
kc.check(isinstance(r.f, np.ndarray) and r.f.shape == (3, 3), "Result.f is a 3 x 3 numpy array")
kc.check(r.c.shape == (3,) and np.allclose(r.c, [r.f[0, 0], r.f[1, 1], r.f[1, 2]]), "c = (C11, C22, C23), c = 1, g = 1")
# a grid given as is, judged against the default target 1e-3: 30 cells across is
# about 0.5-1 % off (docs/accuracy.md), so its estimate misses the target and the
# verdict says so (before, the library's target was 0 and this said 'ok')
kc.check(r.verdict == "uncertain" and np.all(r.err > 1e-3), f"given 30 x 30 grid: verdict {r.verdict}, err {r.err}")
kc.check(kcreep.version().count(".") == 2, f"version {kcreep.version()}")

# the same patch through the command line: the same numbers
row = kc.coefficients(kc.namelist(patch="mx = 30, my = 30", solver="scheme = 'backward'"), folder, "circle")
cli = np.array([[row[f"f{i}{j}"] for j in (1, 2, 3)] for i in (1, 2, 3)])
kc.check(np.max(np.abs(cli - r.f)) <= 1e-14 * np.max(np.abs(cli)), "Python f == command-line f (to the last digit)")

# masks: rows in increasing y, a boolean array; x0, y0 the centre of cell [0, 0]
y, x = np.mgrid[0:24, 0:36]
inside = ((x - 17.5) / 18) ** 2 + ((y - 11.5) / 12) ** 2 <= 1
m = kcreep.solve_mask(inside, 1.0 / 12, 1.0 / 12, x0=-1.5 + 1 / 24, y0=-1 + 1 / 24, nu=0.3, g=2.0,
                      scheme="backward", refine_grid=False, tractions=True)
kc.check(m.n == inside.sum(), f"cells in the patch: {m.n}")
kc.check(m.traction.shape == (m.n, 2, 3), "traction: n x (px, py) x (xi, eta, phi)")
# f11 is minus the sum of px over the cells times the cell area (the table's definition)
kc.close(-m.traction[:, 0, 0].sum() * (1 / 12) ** 2, m.f[0, 0], 1e-12, "f11 from the tractions")
kc.check(m.ix.min() >= 1 and m.ix.max() <= 36 and m.iy.max() <= 24, "cell indices 1-based on the grid")
transposed = kcreep.solve_mask(inside.T, 1.0 / 12, 1.0 / 12, x0=-1 + 1 / 24, y0=-1.5 + 1 / 24, nu=0.3, g=2.0,
                               scheme="backward", refine_grid=False)
kc.check(abs(transposed.f[0, 0] - m.f[0, 0]) > 1e-3 * m.f[0, 0], "rows are y: the transposed patch differs")

# errors carry kcreep's message and status
for call, words in ((lambda: kcreep.solve_ellipse(1, 1, nu=0.7), ["nu", "0.5"]),
                    (lambda: kcreep.solve_ellipse(1, -1), ["semi_a", "> 0"]),
                    (lambda: kcreep.solve_mask(np.zeros((4, 4), bool), 1, 1), ["empty"]),
                    (lambda: kcreep.solve_mask(np.ones(4, bool), 1, 1), ["2-D"]),
                    (lambda: kcreep.solve_ellipse(1, 1, scheme="upwind"), ["scheme", "backward"])):
    try:
        call()
        kc.check(False, f"refused: {words}")
    except kcreep.KcreepError as e:
        kc.check(e.code == 2 and all(w in str(e) for w in words), f"KcreepError {e.code}: {e}")

# one Solver, the in-loop case: new masks on the same grid reuse the operator table
s = kcreep.Solver(nu=0.25, g=1.0, scheme="backward", refine_grid=False)
first = s.solve_mask(inside, 1.0 / 12, 1.0 / 12)
inside[0, 17] = False
second = s.solve_mask(inside, 1.0 / 12, 1.0 / 12)
kc.check(s.reuse_count == 1 and second.n == first.n - 1, f"operator table reused ({s.reuse_count})")
# the warm start (GMRES from the last solution on the grid) meets the same
# tolerance as a cold one: coefficients agree to the solver's accuracy (the
# iterative path agrees with dense LU to ~1e-10 at tolerance 1e-11, see
# test_solver_paths; 1e-9 leaves room)
iterative = dict(nu=0.25, g=1.0, scheme="backward", method="iterative", refine_grid=False)
warm_solver = kcreep.Solver(**iterative)
warm_solver.solve_mask(~inside[::-1], 1.0 / 12, 1.0 / 12)      # another patch on the same grid first
warm = warm_solver.solve_mask(inside, 1.0 / 12, 1.0 / 12)
cold = kcreep.Solver(**iterative).solve_mask(inside, 1.0 / 12, 1.0 / 12)
kc.check(np.max(np.abs(warm.f - cold.f)) <= 1e-9 * np.max(np.abs(cold.f)),
         f"warm-started solve == cold solve (max diff {np.max(np.abs(warm.f - cold.f)):.2e})")
s.set_material(g=1.0, nu=0.3)
s.solve_mask(inside, 1.0 / 12, 1.0 / 12)
kc.check(s.reuse_count == 1, "a new material rebuilds the table")

# extrapolation gives an error estimate
e = kcreep.Solver(nu=0.25, scheme="backward", extrapolate_levels=2).solve_ellipse(1, 1, 20, 20)
kc.check(np.all(np.isfinite(e.ext_error)) and np.all(e.ext_error > 0), f"error estimate {e.ext_error}")
kc.check(np.all(np.isnan(r.ext_error)), "no estimate without extrapolation: NaN")

# error control through the API: kcreep chooses the grids for the target and
# the estimate comes back; against the refined table's circle (with its u)
ref = [r for r in kcreep.table.read(os.path.join(source_dir, "docs", "data", "kalker_refined.dat"))
       if r["a_over_b"] == 1 and r["nu"] == 0.25][0]
controlled = kcreep.Solver(nu=0.25, target_error=1e-3, refine_grid=True, method="iterative").solve_ellipse(1.0, 1.0)
kc.check(np.all(np.isfinite(controlled.err)) and np.all(controlled.err > 0) and controlled.n > 0,
         f"relative error estimate {controlled.err} ({controlled.n} cells solved)")
kc.check(abs(controlled.c[0] / ref["c11"] - 1) <= controlled.err[0] + ref["u11"] / ref["c11"],
         f"the estimate bounds the error of C11 ({controlled.c[0]:.5f} vs {ref['c11']})")
# method 'auto' (the default) answers the same ellipse from the refined table: nothing solved
auto = kcreep.Solver(nu=0.25, target_error=1e-3, refine_grid=True).solve_ellipse(1.0, 1.0)
kc.check(auto.n == 0 and auto.verdict == "ok" and abs(auto.c[0] / ref["c11"] - 1) < 1e-5,
         f"method 'auto', target 1e-3: the refined table's C11 ({auto.c[0]:.5f}), no cells, verdict {auto.verdict}")
try:
    kcreep.Solver(target_error=2.0)
    kc.check(False, "target_error 2 refused")
except kcreep.KcreepError as e:
    kc.check("target_error" in str(e), f"KcreepError: {e}")
# cell_budget: the finest level keeps to it; a small budget at a tight target
# stops early ('uncertain', the warning names the setting), a larger one goes
# further and its estimates are smaller (circle at 2e-4: 5,000 cells stop at
# 80 across, 15,000 at about 136, both short of the target)
small, large = (kcreep.Solver(nu=0.25, target_error=2e-4, refine_grid=True, method="iterative",
                              cell_budget=b).solve_ellipse(1.0, 1.0) for b in (5000.0, 15000.0))
# (the base levels are scaled to the budget and rounded to whole cells across:
# up to about 1 % over it, 5,024 cells measured for 5,000)
kc.check(small.n <= 1.01 * 5000 and 5000 < large.n <= 1.01 * 15000,
         f"finest levels {small.n}, {large.n} cells within the budgets")
kc.check(small.verdict == "uncertain" and any("cell_budget" in w for w in small.warnings),
         f"budget stop: verdict {small.verdict}, warnings {small.warnings}")
kc.check(np.all(large.err < small.err), f"estimates {small.err} -> {large.err} with the larger budget")
try:
    kcreep.Solver(target_error=1e-3, refine_grid=True, cell_budget=10.0).solve_ellipse(1.0, 1.0)
    kc.check(False, "cell_budget 10 refused")
except kcreep.KcreepError as e:
    kc.check("cell_budget = 10" in str(e), f"KcreepError: {e}")

# the normal problem from a gap (Hertz: a sphere-like quadratic gap) and FASTSIM on its pressure
gy, gx = np.mgrid[0:64, 0:64]
xs, ys = -1.6 + (gx + 0.5) * 0.05, -1.6 + (gy + 0.5) * 0.05
quadratic = xs ** 2 / (2 * 10.0) + ys ** 2 / (2 * 10.0)
hs = kcreep.Solver(nu=0.28, g=82000.0, scheme="backward", refine_grid=False)
rg = hs.solve_gap(quadratic, 0.05, 0.05, -1.6 + 0.025, -1.6 + 0.025, normal_force=5000.0)
kc.close(rg.fn, 5000.0, 1e-8, "normal_force prescribed through Python")
# Hertz: a = (3 F R / (4 E*))^(1/3), R = 10 the relative radius of the gap, E* = g / (1 - nu)
# for identical bodies; a is 14 cells here and the staircase area was measured 1.6 % above
# pi a^2, so 5 %
estar = 82000.0 / (1 - 0.28)
a_hertz = (3 * 5000.0 * 10.0 / (4 * estar)) ** (1 / 3)
kc.close(rg.n * 0.05 ** 2, np.pi * a_hertz ** 2, 0.05, "contact area near Hertz's")
forces, adhesion = hs.fastsim(0.3, [[1e-7, 0, 0], [1e-1, 0, 0]])
kc.close(-forces[0, 0] / 1e-7, rg.f[0, 0], 1e-3, "FASTSIM slope on the normal pressure = f11")
kc.close(-forces[1, 0], 0.3 * rg.fn, 1e-3, "FASTSIM saturates at mu Fn")
kc.check(adhesion[0] > 0.99 and adhesion[1] < 0.05, f"adhesion {adhesion}")
# the exact rolling solution (docs/rolling.md) on the same patch and pressure: the slope f11
# (a few trailing cells slip at 1e-7: measured within 1e-4), full slip exactly mu Fn
forces, adhesion = hs.rolling(0.3, [[1e-7, 0, 0], [1e-1, 0, 0]])
kc.close(-forces[0, 0] / 1e-7, rg.f[0, 0], 1e-3, "rolling slope on the normal pressure = f11")
# full slip: every cell at mu pn, the directions bent a little by the elastic slip (measured 4e-5)
kc.close(-forces[1, 0], 0.3 * rg.fn, 1e-4, "rolling saturates at mu Fn")
kc.check(adhesion[0] > 0.95 and adhesion[1] == 0, f"rolling adhesion {adhesion}")
try:
    kcreep.Solver().solve_gap(quadratic, 0.05, 0.05, approach=0.01, normal_force=10.0)
    kc.check(False, "approach and normal_force together refused")
except kcreep.KcreepError as e:
    kc.check("exactly one" in str(e), f"KcreepError: {e}")

# the spin centre: about (xs, ys) the phi column is f(:, 3) - xs f(:, 2) + ys f(:, 1) (the
# rigid slip xi - phi (y - ys), eta + phi (x - xs)); the same discrete operator, so to round-off
about = kcreep.Solver(nu=0.25, spin_centre=(0.3, -0.2), refine_grid=False).solve_mask(inside, 1.0 / 12, 1.0 / 12, x0=-1.5 + 1 / 24,
                                                                     y0=-1 + 1 / 24)
origin = kcreep.Solver(nu=0.25, refine_grid=False).solve_mask(inside, 1.0 / 12, 1.0 / 12, x0=-1.5 + 1 / 24, y0=-1 + 1 / 24)
expected = origin.f[:2, 2] - 0.3 * origin.f[:2, 1] + (-0.2) * origin.f[:2, 0]
kc.check(np.max(np.abs(about.f[:2, 2] - expected)) <= 1e-9 * np.max(np.abs(origin.f)),
         f"spin centre (0.3, -0.2): f13, f23 {about.f[:2, 2]} vs {expected}")
# two bodies given by E and nu: steel on steel is g = E / (2 (1 + nu)), nu
steel = kcreep.Solver(bodies=(210000.0, 0.28, 210000.0, 0.28)).solve_ellipse(1, 1, 20, 20)
plain = kcreep.Solver(g=210000.0 / 2.56, nu=0.28).solve_ellipse(1, 1, 20, 20)
kc.check(np.max(np.abs(steel.f - plain.f)) <= 1e-12 * np.max(np.abs(plain.f)), "bodies (E, nu) = combined g, nu")

# method = 'table' (ellipses from the refined table): the table's values at its points, the stated
# uncertainty as err, no tractions, FASTSIM on the patch's grid, refusals
ref = [r for r in kcreep.table.read(os.path.join(source_dir, "docs", "data", "kalker_refined.dat"))
       if abs(r["a_over_b"] - 2) < 1e-9 and abs(r["nu"] - 0.25) < 1e-9][0]
ref_c = np.array([ref["c11"], ref["c22"], ref["c23"]])
ref_u = np.array([ref["u11"], ref["u22"], ref["u23"]]) / ref_c
tab = kcreep.solve_ellipse(2.0, 1.0, nu=0.25, mx=20, my=20, method="table")
kc.check(np.all(np.abs(tab.c / ref_c - 1) <= 1e-14) and tab.n == 0 and tab.verdict == "ok",
         f"method='table' at a/b = 2, nu = 0.25: the table's C {tab.c}, no cells solved, verdict {tab.verdict}")
kc.check(np.allclose(tab.err, ref_u, rtol=1e-5), f"method='table': err = u/C of the table {tab.err}")
# a target tighter than the table's u/C: uncertain, with one warning naming the table
ts = kcreep.Solver(method="table", target_error=0.5 * float(min(ref_u[0], ref_u[1], ref_u[2] / 3)))
tu = ts.solve_ellipse(2.0, 1.0, 20, 20)
kc.check(tu.verdict == "uncertain" and len(tu.warnings) == 1 and "refined table" in tu.warnings[0],
         f"method='table' with a target below its u/C: {tu.verdict}, {tu.warnings}")
forces, _ = ts.fastsim(0.3, [[1e-9, 0, 0]], pressure=np.ones((20, 20)))
kc.close(-forces[0, 0] / 1e-9, tu.f[0, 0], 1e-9, "method='table': FASTSIM slope = f11 of the table")
for call, words in ((lambda: ts.solve_ellipse(2.0, 1.0, 20, 20, tractions=True), ["no tractions", "table"]),
                    (lambda: kcreep.solve_mask([[1, 1], [1, 1]], 1.0, 1.0, method="table"), ["only for ellipses"]),
                    (lambda: kcreep.solve_ellipse(20.0, 1.0, method="table"), ["a/b = 20", "0.1 <= a/b <= 10"])):
    try:
        call()
        kc.check(False, f"refused: {words}")
    except kcreep.KcreepError as e:
        kc.check(all(w in str(e) for w in words), f"method='table' refused: {e}")

# kcreep.table reads the command line's table
rows = kcreep.table.read(os.path.join(folder, "circle.tab"))
kc.check(len(rows) == 1 and rows[0]["case"] == "circle" and rows[0]["f11"] == row["f11"], "kcreep.table.read")

# pip install ./python (Debian's setuptools, no network) builds libkcreep.so into
# the package: it imports from any folder with no setting, numpy its only
# dependency (from a copy of the repository: pip builds in the source folder,
# which must stay clean)
copy, target = os.path.join(folder, "repo"), os.path.join(folder, "site")
kc.copy_repository(source_dir, copy)
proc = subprocess.run([sys.executable, "-m", "pip", "install", "--no-build-isolation", "--no-deps", "--no-index",
                       "--target", target, os.path.join(copy, "python")], capture_output=True, text=True)
kc.check(proc.returncode == 0, "pip install ./python" + ("" if proc.returncode == 0 else ": " + proc.stderr[-500:]))
kc.check(os.path.isfile(os.path.join(target, "kcreep", "libkcreep.so")), "the package carries libkcreep.so")
requires = [line.split(":", 1)[1].strip() for meta in glob.glob(os.path.join(target, "kcreep-*-info", "METADATA"))
            for line in open(meta) if line.startswith("Requires-Dist:")]
kc.check(requires == ["numpy"], f"numpy its only dependency ({requires})")
code = "import kcreep, sys; print(kcreep.__file__); print(kcreep.solve_ellipse(1, 1, mx=30, my=30, scheme='backward').f[0, 0])"
env = {k: v for k, v in os.environ.items() if k not in ("KCREEP_LIBRARY", "LD_LIBRARY_PATH")}
shutil.rmtree(copy)   # nothing of the source tree left to fall back on
proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=folder,
                      env=dict(env, PYTHONPATH=target))
lines = proc.stdout.split()
kc.check(proc.returncode == 0 and lines[0].startswith(target) and abs(float(lines[1]) - r.f[0, 0]) <= 1e-14 * r.f[0, 0],
         "the installed package, no setting, another folder: the same f11" + ("" if proc.returncode == 0 else proc.stderr[-500:]))
proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=folder,
                      env=dict(env, PYTHONPATH=target, KCREEP_LIBRARY=os.path.join(folder, "nowhere.so")))
kc.check(proc.returncode != 0 and "KCREEP_LIBRARY" in proc.stderr, "a wrong KCREEP_LIBRARY is named in the error")
kc.finish()
