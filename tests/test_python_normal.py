"""The normal contact problem through the Python package: kcreep.solve_gap on
a numpy gap gives the same contact area, force, pressure and coefficients as
the command line's shape = 'gap' on the same grid; bad arguments raise
KcreepError with kcreep's message.

usage: /usr/bin/python3 test_python_normal.py KCREEP SOURCE_DIR   (needs numpy)
"""
import os
import sys

import kctest as kc

folder = kc.setup()
source_dir = os.path.abspath(sys.argv[2])
sys.path.insert(0, os.path.join(source_dir, "python"))
import numpy as np  # noqa: E402
import kcreep  # noqa: E402

os.environ.pop("KCREEP_LIBRARY", None)
mx, my, d = 40, 30, 0.025
x0, y0 = -(mx - 1) * d / 2, -(my - 1) * d / 2
x = x0 + d * np.arange(mx)
y = y0 + d * np.arange(my)
gap = x[None, :] ** 2 / (2 * 2.0) + y[:, None] ** 2 / (2 * 1.0) + 0.01 * x[None, :]   # rows in increasing y
r = kcreep.solve_gap(gap, d, d, x0=x0, y0=y0, normal_force=0.002, g=1.0, nu=0.3, tractions=True)
kc.check(abs(r.fn / 0.002 - 1) < 1e-12 and r.normal_residual <= 1e-10, f"solve_gap: fn {r.fn}, residual {r.normal_residual:.1e}")
kc.check(r.pressure.shape == (r.n,) and abs(r.pressure.sum() * d * d / r.fn - 1) < 1e-12 and r.pressure.max() == r.pmax,
         "pressure per patch cell: sums to fn, maximum pmax")
kc.check(r.traction.shape == (r.n, 2, 3), "tractions of the contact cells")

# the same through the command line (rx = 2, ry = 1, lx = 0.01 on the same grid)
row = kc.coefficients(f"&patch shape='gap', mx={mx}, my={my}, dx={d}, dy={d}, x0={x0!r}, y0={y0!r} /\n"
                      f"&material g=1.0, nu=0.3 /\n&normal rx=2, ry=1, lx=0.01, normal_force=0.002 /\n", folder, "cli")
cli = np.array([[row[f"f{i}{j}"] for j in (1, 2, 3)] for i in (1, 2, 3)])
kc.check(int(row["n"]) == r.n and abs(row["approach"] / r.approach - 1) < 1e-12 and abs(row["pmax"] / r.pmax - 1) < 1e-12,
         f"command line: the same {r.n} cells (of {mx * my}), approach and pmax "
         f"({row['approach'] / r.approach - 1:.1e}, {row['pmax'] / r.pmax - 1:.1e})")
kc.check(np.allclose(cli, r.f, rtol=1e-12, atol=0), "command line: the same creep-force matrix")

# dissimilar bodies: the approach prescribed, the force from the exact 1/E*
rb = kcreep.solve_gap(gap, d, d, x0=x0, y0=y0, approach=r.approach, bodies=(210e3, 0.3, 70e3, 0.33))
c_same, c_bodies = (1 - 0.3) / 1.0, (1 - 0.09) / 210e3 + (1 - 0.33**2) / 70e3
kc.check(rb.n == r.n and abs(rb.fn / (r.fn * c_same / c_bodies) - 1) < 1e-8,
         "bodies: the same area at the same approach, the force scaled by the compliance ratio")

for label, call, phrase in [
    ("both loads", lambda: kcreep.solve_gap(gap, d, d, approach=0.1, normal_force=1.0), "exactly one"),
    ("negative force", lambda: kcreep.solve_gap(gap, d, d, normal_force=-1.0), "normal force must be finite and > 0"),
    ("no interpenetration", lambda: kcreep.solve_gap(gap + 1.0, d, d, approach=0.5), "no interpenetration"),
    ("NaN", lambda: kcreep.solve_gap(np.where(gap > 0.01, np.nan, gap), d, d, approach=0.01), "finite numbers only"),
]:
    try:
        call()
        kc.check(False, f"{label}: KcreepError expected")
    except kcreep.KcreepError as e:
        kc.check(e.code == 2 and phrase in str(e), f"{label}: KcreepError {e.code}: {e}")
kc.finish()
