"""Narrow patches (a/b -> 0): C11 -> pi^2/(4(1-nu)), C22 -> pi^2/4.

a/b = 0.05 on a 10 x 200 grid (square cells). The table's asymptote
branch gives the reference (klt columns). Measured errors (2026-11):
collocation C11 +6.0 .. +8.0 %, C22 +8.0 .. +8.7 %; backward C11 +2.2 ..
+3.9 %, C22 +3.9 .. +4.4 %: ten cells along x is coarse. Tolerances are
those maxima rounded up. Halving the cell size must reduce the error
(checked for one case, the backward scheme at nu = 0.25)."""
import math
import kctest as kc

folder = kc.setup()
tolerance = {"collocation": 0.095, "backward": 0.048}
for scheme, tol in tolerance.items():
    for nu in (0.0, 0.25, 0.5):
        row = kc.coefficients(kc.namelist("semi_a=0.05, semi_b=1, mx=10, my=200", f"nu={nu}",
                                          f"{kc.scheme_setting(scheme, 0.5)}"), folder)
        kc.close(row["klt11"], math.pi**2 / (4 * (1 - nu)), 1e-12, f"asymptote C11 nu={nu}")
        kc.close(row["klt22"], math.pi**2 / 4, 1e-12, f"asymptote C22 nu={nu}")
        kc.close(row["c11"], row["klt11"], tol, f"{scheme} nu={nu} C11 vs narrow asymptote")
        kc.close(row["c22"], row["klt22"], tol, f"{scheme} nu={nu} C22 vs narrow asymptote")
coarse = kc.coefficients(kc.namelist("semi_a=0.05, semi_b=1, mx=8, my=160", "nu=0.25", "scheme='backward'"), folder)
fine = kc.coefficients(kc.namelist("semi_a=0.05, semi_b=1, mx=16, my=320", "nu=0.25", "scheme='backward'"), folder)
kc.check(abs(fine["c11"] / fine["klt11"] - 1) < abs(coarse["c11"] / coarse["klt11"] - 1),
         f"narrow C11 error shrinks with the mesh: {coarse['c11']:.4f} -> {fine['c11']:.4f} (limit {fine['klt11']:.4f})")
kc.finish()
