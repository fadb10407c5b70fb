"""kcreep.ContactTable (python/kcreep/contact_table.py) and kcreep_take_wheel_rail_row:

- at() at a row is that row; between rows every column lies between the
  neighbours' (linear), continuous across a row; out of range refused;
- the exact path (exact=True) runs on the row's own patch and pressure: at a
  small creepage it is the row's linear forces -f (xi, eta, phi) of the
  table's C11, C22 (f = G c^2 C, c^2 = area / pi) within the discretisation;
  forces between rows continuous (the weighted rows);
- the fast model at a row within 1 % of mu Fn of exact=True: skipped while
  the library has no Solver.fast_forces (forces(exact=False) is FASTSIM then,
  up to 8-15 % of mu Fn off on such patches, docs/fastsim.md);
- FASTSIM ('aligned') finite on S1002/UIC60 patches whose edge pressures
  underflow its slip projection (it gave NaN before the fix in aligned_slip);
- patches matched across shifts and flags for intervals too coarse;
- exact rolling on a flange row where Newton stalls (the creepage path);
- force_cells: rows' force grids coarsened (kcreep_coarsen_patch), their
  fast model held to their exact forces, those near the full grid's; by
  default to at most 4000 cells (FORCE_CELLS), 0 the rows' own grids.

usage: /usr/bin/python3 test_contact_table.py KCREEP SOURCE_DIR   (needs numpy)
"""
import math
import os
import sys

import kctest as kc

folder = kc.setup()
source_dir = os.path.abspath(sys.argv[2])
sys.path.insert(0, os.path.join(source_dir, "python"))
import numpy as np  # noqa: E402
import kcreep  # noqa: E402
from kcreep.library import Solver  # noqa: E402


circle = kc.circle_profile


# a crowned wheel (profile radius 300 mm) on a 300 mm rail crown (one Hertzian patch a shift)
for name, text in {"wheel.dat": circle(300, 40, True), "rail.dat": circle(250, 35, False)}.items():
    with open(os.path.join(folder, name), "w") as f:
        f.write(text)
wheel, rail = os.path.join(folder, "wheel.dat"), os.path.join(folder, "rail.dat")
G, NU, FORCE, MU = 82000.0, 0.28, 80000.0, 0.3
table = kcreep.ContactTable(wheel, rail, [-4.0, 0.0, 4.0], g=G, nu=NU, vertical_force=FORCE, target_error=1e-2,
                            cell_budget=600.0, flange_back_position=-72.5, threads=1)
t = table.table
kc.check(t["shift"].size == 3 and len(table._tracks) == 1, f"one patch a shift, one track ({len(table._tracks)})")

# at(): rows, between rows, continuity, range
for k in range(3):
    p = table.at(t["shift"][k])
    kc.check(len(p) == 1 and all(p[0][c] == t[c][k] for c in table.columns),
             f"at({t['shift'][k]:g}) is row {k}")
numeric = [c for c in table.columns if c not in ("shift", "patch", "verdict", "kind")]
for s, (a, b) in ((-1.3, (0, 1)), (2.9, (1, 2))):
    p = table.at(s)[0]
    inside = [c for c in numeric if min(t[c][a], t[c][b]) - 1e-12 <= p[c] <= max(t[c][a], t[c][b]) + 1e-12]
    kc.check(len(inside) == len(numeric), f"at({s}) between its neighbours in every column "
             f"(outside: {sorted(set(numeric) - set(inside))})")
    kc.check(p["kind"] == t["kind"][a] == t["kind"][b], f"at({s}): the kind of its rows ({p['kind']})")
lo, hi = table.at(-1e-9)[0], table.at(1e-9)[0]
kc.check(all(abs(lo[c] - hi[c]) <= 1e-8 * max(1.0, abs(lo[c])) for c in numeric), "at() continuous across a row")
try:
    table.at(4.5)
    kc.check(False, "at(4.5) beyond the table refused")
except kcreep.KcreepError as e:
    kc.check(e.code == 2 and "4.5" in str(e), f"at(4.5) refused: {e}")

# the exact path on the row's patch: small creepage against the row's linear forces
small = 1e-6
creep = np.array([[small, 0, 0], [0, small, 0]])
for k in (0, 1):
    f = table.forces(t["shift"][k], MU, creep, exact=True)[0]
    c2 = t["area"][k] / math.pi
    f11, f22 = G * c2 * t["c11"][k], G * c2 * t["c22"][k]
    # measured: 0.76 % (C11) and 0.91 % (C22) with cell_budget 600 (rolling on the row's grid
    # against the row's error-controlled C's, whose err is up to 1 %)
    e11, e22 = abs(-f[0, 0] / small / f11 - 1), abs(-f[1, 1] / small / f22 - 1)
    kc.check(e11 < 0.02 and e22 < 0.02, f"row {k}: exact rolling at 1e-6 is -f11 xi, -f22 eta of the row "
             f"({100 * e11:.2f} %, {100 * e22:.2f} %)")
mid = table.forces(-2.0, MU, [[1e-3, 5e-4, 0]], exact=True)[0]
ends = [table.forces(s, MU, [[1e-3, 5e-4, 0]], exact=True)[0] for s in (-4.0, 0.0)]
# the same exact solves from other starts: within 1e-6 of mu Fn (both stop at the residual
# 1e-7, the default; measured: 6e-13 of mu Fn)
gap = np.abs(mid - 0.5 * (ends[0] + ends[1]))[0, :2].max() / (MU * FORCE)
kc.check(gap <= 1e-6, f"forces between rows: the rows' mean ({gap:.1e} of mu Fn)")

# the C API's kcreep_wheel_rail_forces: the rows' forces weighted as at(), the same as Python's per-row solvers
import ctypes  # noqa: E402
from kcreep.library import _lib  # noqa: E402
src = table._source
creep2 = np.ascontiguousarray([[1e-3, 5e-4, 1e-5], [-2e-3, 1e-3, 0.0]])
for exact in (0, 1):
    out = np.empty((1, 2, 3))
    code = _lib.kcreep_wheel_rail_forces(src._handle, -1.3, MU, 2, 1, creep2.ctypes.data, exact, out.ctypes.data)
    ref = table.fastsim_forces(-1.3, MU, creep2)[0] if exact == 0 else table.forces(-1.3, MU, creep2, exact=True)[0]
    # FASTSIM identical; exact rolling from other starts within 1e-6 of mu Fn (both stop at
    # the residual 1e-7; measured: 3e-10 of mu Fn)
    gap = np.abs(out[0] - ref)[:, :2].max() / (MU * FORCE)
    kc.check(code == 0 and gap <= (1e-6 if exact else 1e-12),
             f"C forces (exact={exact}) at -1.3 mm are Python's ({code}; {gap:.1e} of mu Fn)")
code = _lib.kcreep_wheel_rail_forces(src._handle, -1.3, MU, 2, 2, creep2.ctypes.data, 0, out.ctypes.data)
kc.check(code == 2, "C forces with n_patches = 2 where the shift has 1 refused")
values, n = np.empty((1, len(table.columns))), ctypes.c_int()
code = _lib.kcreep_wheel_rail_at(src._handle, -1.3, 0, values.ctypes.data, None, None, ctypes.byref(n))
kc.check(code == 2, "C at() with capacity 0 refused")
code = _lib.kcreep_wheel_rail_at(src._handle, -1.3, 1, values.ctypes.data, None, None, ctypes.byref(n))
kc.check(code == 0 and n.value == 1 and np.allclose(values[0], [float(v == "flange") if c == "kind" else v
                                                         for c, v in table.at(-1.3)[0].items()]),
         "C at() (rows, weights NULL) is Python's")

# the fast model at a row within 1 % of mu Fn of the exact path (issue 48)
if hasattr(Solver, "fast_forces"):
    rng = np.random.default_rng(48)
    creeps = rng.uniform(-1, 1, (20, 3)) * [3e-3, 3e-3, 3e-5]
    for k in range(3):
        s = t["shift"][k]
        fast = table.forces(s, MU, creeps)[0]
        exact = table.forces(s, MU, creeps, exact=True)[0]
        worst = np.max(np.abs(fast[:, :2] - exact[:, :2])) / (MU * t["fn"][k])
        kc.check(worst <= 0.01, f"row {k}: fast model within 1 % of mu Fn of exact ({100 * worst:.2f} %)")
else:
    print("skip: the fast model's check (no Solver.fast_forces in this build; forces(exact=False) is FASTSIM)")

# FASTSIM finite where edge pressures underflowed its slip projection (NaN before)
profiles = os.path.join(source_dir, "..", "shared", "profiles")
s1002 = kcreep.ContactTable(os.path.join(profiles, "MBench_S1002_v3.prw"), os.path.join(profiles, "MBench_UIC60_v3.prr"),
                            [4.0, 5.0, 6.0], g=G, nu=NU, vertical_force=70e3, target_error=1e-2, cell_budget=1000.0,
                            threads=1, force_cells=0)
bad = []
for r in range(s1002.table["shift"].size):
    for rule in ("aligned", "separate", "weighted"):
        f = s1002.solver(r).fastsim(MU, [[0, 1e-3, 0], [1e-3, 1e-3, 1e-4]], rule=rule)[0]
        if not np.all(np.isfinite(f)):
            bad.append((s1002.table["shift"][r], rule))
kc.check(not bad, f"FASTSIM finite on every S1002 row and rule (NaN: {bad})")
kc.check(s1002.fast_model in ("fastsim", "fast_forces"), f"fast model named ({s1002.fast_model})")
# 4 -> 5 -> 6 mm: the tread patch moves towards the flange; the table says whether it follows
kc.check(len(s1002.flags) == 2, f"one flag list per interval ({s1002.flags})")

# force_cells: the rows' force models on their normal grids coarsened (kcreep_coarsen_patch)
coarse = kcreep.ContactTable(os.path.join(profiles, "MBench_S1002_v3.prw"), os.path.join(profiles, "MBench_UIC60_v3.prr"),
                             [4.0, 5.0, 6.0], g=G, nu=NU, vertical_force=70e3, target_error=1e-2, cell_budget=1000.0,
                             threads=1, force_cells=350)
rng = np.random.default_rng(7)
creeps = rng.normal(size=(40, 3)) * [1e-3, 1e-3, 2e-4]
for r in (0, 1):
    full_n, n = s1002.solver(r)._result(False).n, coarse.solver(r)._result(False).n
    shift, fn = coarse.table["shift"][r], coarse.table["fn"][r]
    kc.check(full_n > 1000 and 100 < n <= 350, f"row {r}: force grid {full_n} -> {n} cells (at most 350)")
    # the normal force kept: linear forces at a tiny creepage are the row's -f11 xi within the
    # coarse grid's discretisation (measured 1.3-2.0 % on these rows, full grids 0.3-1.0 %)
    small = coarse.solver(r).rolling(MU, [[1e-7, 0, 0]])[0][0, 0] / -1e-7
    f11 = G * coarse.table["area"][r] / math.pi * coarse.table["c11"][r]
    kc.check(abs(small / f11 - 1) < 0.04, f"row {r}: -Fx/xi on the coarse grid {small:.4g} against f11 {f11:.4g}")
    fast = coarse.solver(r).fast_forces(MU, creeps)
    exact = coarse.solver(r).rolling(MU, creeps)[0]
    full = s1002.solver(r).rolling(MU, creeps)[0]
    e_fast = np.hypot(*(fast - exact)[:, :2].T).max() / (MU * fn)
    e_grid = np.hypot(*(exact - full)[:, :2].T).max() / (MU * fn)
    # measured: fast model 0.1-0.3 % of its own grid's exact forces; coarse against full grid
    # 1.0-2.5 % (S1002 rows at 0, 3, 8 mm, 100 creepages), the price of force_cells
    kc.check(e_fast <= 0.01, f"row {r}: fast model on the coarse grid within 1 % of its exact forces "
             f"({100 * e_fast:.2f} %)")
    kc.check(e_grid <= 0.04, f"row {r}: coarse grid's exact forces within 4 % of mu Fn of the full grid's "
             f"({100 * e_grid:.2f} %)")
# the default force grid: at the default target the 0 mm row's normal grid has 7010 cells,
# coarsened to at most FORCE_CELLS (4000; 3547 cells measured) unless force_cells = 0
files = os.path.join(profiles, "MBench_S1002_v3.prw"), os.path.join(profiles, "MBench_UIC60_v3.prr")
own = kcreep.ContactTable(*files, [0.0, 0.1], g=G, nu=NU, vertical_force=70e3, threads=1, force_cells=0)
default = kcreep.ContactTable(*files, [0.0, 0.1], g=G, nu=NU, vertical_force=70e3, threads=1)
n_own, n_default = own.solver(0)._result(False).n, default.solver(0)._result(False).n
kc.check(n_own > 4000 and 1000 < n_default <= 4000 and default.force_cells == 4000,
         f"default force grid: the 0 mm row's {n_own} cells -> {n_default} (at most 4000)")
try:
    kcreep.ContactTable(wheel, rail, [-4.0, 0.0], g=G, nu=NU, vertical_force=FORCE, target_error=1e-2,
                        cell_budget=600.0, flange_back_position=-72.5, threads=1, force_cells=5)
    kc.check(False, "force_cells = 5 refused")
except kcreep.KcreepError as e:
    kc.check(e.code == 2 and "force_cells = 5" in str(e), f"force_cells = 5 refused: {e}")
try:
    plain = Solver(g=G, nu=NU, threads=1)
    plain.solve_ellipse(1.0, 1.0, 10, 10)
    plain.coarsen_patch(20)
    kc.check(False, "coarsen_patch without a normal problem refused")
except kcreep.KcreepError as e:
    kc.check(e.code == 2 and "no normal problem" in str(e), f"coarsen_patch without a normal problem refused: {e}")

# exact rolling where Newton stalls: the S1002 flange row at 8 mm (the table's solver's patch), a creepage where
# the spin moment changes sign; from any start Newton's steps were damped to a quarter and it
# stopped at 2e-5 after 60 steps ("did not converge"); now it follows the creepage path. The
# answer equals a path of 20 steps taken by hand (measured 1.4e-9 of mu Fn).
flange = kcreep.ContactTable(os.path.join(profiles, "MBench_S1002_v3.prw"), os.path.join(profiles, "MBench_UIC60_v3.prr"),
                             [7.0, 8.0, 9.0], g=G, nu=NU, vertical_force=70e3, target_error=1e-2, cell_budget=1000.0,
                             threads=1)
row = flange._terms(8.0)[0][0][0]
hard = np.array([-3.23196e-4, -1.3665e-4, -1.99434e-4])
try:
    direct = flange.solver(row).rolling(MU, [hard])[0][0]
except kcreep.KcreepError as e:
    direct = np.full(3, np.nan)
    print(f"rolling failed: {e}")
by_hand = Solver(g=G, nu=NU, threads=1)
by_hand.take_wheel_rail_row(flange._source, row)
by_hand.coarsen_patch(flange.force_cells)   # the table's solver's patch (the row's grid may pass FORCE_CELLS)
for k in range(1, 21):
    path = by_hand.rolling(MU, [hard * k / 20])[0][0]
gap = np.abs(direct - path)[:2].max() / (MU * flange.table["fn"][row])
kc.check(gap <= 1e-6, f"flange row at 8 mm: exact rolling converges where Newton stalled, the path's answer "
         f"({gap:.1e} of mu Fn)")

# kcreep_take_wheel_rail_row: a row out of range, a handle without a table
try:
    Solver(g=G, nu=NU).take_wheel_rail_row(table._source, 3)
    kc.check(False, "row 3 of a 3-row table refused")
except kcreep.KcreepError as e:
    kc.check(e.code == 2 and "row = 3" in str(e) and "0 to 2" in str(e), f"row 3 refused: {e}")
try:
    Solver(g=G, nu=NU).take_wheel_rail_row(Solver(g=G, nu=NU), 0)
    kc.check(False, "a source without a table refused")
except kcreep.KcreepError as e:
    kc.check(e.code == 6 and "no table" in str(e), f"a source without a table refused: {e}")
kc.finish()
