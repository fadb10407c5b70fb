"""FASTSIM flexibilities L1, L2, L3 (columns L1 L2 L3).

L1 = I1/f11, L2 = I1/f22, L3 = I3/f23 with I1 = Int (x_l - x) dA and
I3 = Int (x_l^2 - x^2)/2 dA over the cells, x_l the leading edge of each
strip segment. Checked three ways:
 1. a rectangle, where I1 = 4 A^2 B and I3 = 4/3 A^3 B in closed form
    (round-off tolerance 1e-12);
 2. a non-convex mask with several segments per row against an independent
    Python evaluation of the same integrals (1e-12);
 3. ellipses against Kalker's formulas L1 = 8a/(3 C11 G),
    L2 = 8a/(3 C22 G), L3 = pi a sqrt(a/b)/(4 C23 G) evaluated with
    kcreep's own C's: they differ only by the staircase boundary of the
    cells against the true ellipse in I1, I3 (and c). Measured |L/L_Kalker - 1|:
    circle 40 x 40: 0.95 % (L1), 1.25 % (L3); 80 x 80: 0.09 %, 0.08 %;
    160 x 160: 0.010 %, 0.023 %; a/b = 2 on 160 x 80: 0.17 %, 0.22 %;
    240 x 120: 0.002 %, 0.023 %. The test runs the 160 x 160 circle and the
    240 x 120 a/b = 2 ellipse (iterative path, under a second each) with
    tolerance 0.05 %."""
import math
import kctest as kc

folder = kc.setup()

# 1. rectangle 12 x 6 cells of 0.1: A = 0.6, B = 0.3
A, B = 0.6, 0.3
rows = ["#" * 12] * 6
inline = ", ".join(f"'{r}'" for r in rows)
for scheme in ("collocation", "backward"):
    r = kc.coefficients(kc.namelist(f"shape='mask', mask_rows={inline}, dx=0.1, dy=0.1, x0=-0.55, y0=-0.25",
                                    "g=3, nu=0.3", f"scheme='{scheme}'"), folder)
    kc.close(r["L1"] * r["f11"], 4 * A**2 * B, 1e-12, f"{scheme} rectangle: L1 f11 = 4 A^2 B")
    kc.close(r["L2"] * r["f22"], 4 * A**2 * B, 1e-12, f"{scheme} rectangle: L2 f22 = 4 A^2 B")
    kc.close(r["L3"] * r["f23"], 4 / 3 * A**3 * B, 1e-12, f"{scheme} rectangle: L3 f23 = 4/3 A^3 B")

# 2. non-convex mask, several segments per row
rows = ["##..###.", ".######.", "#.#.#.##", "########"]
dx, dy, x0, y0 = 0.2, 0.15, -0.7, -0.2
I1 = I3 = 0.0
h = dx / 2
for iy, row in enumerate(rows):
    lead = None
    for ix in range(len(row) - 1, -1, -1):
        if row[ix] != "#":
            lead = None
            continue
        x = x0 + ix * dx
        if lead is None:
            lead = x + h
        I1 += 2 * h * (lead - x) * dy
        I3 += (h * (lead**2 - x**2) - h**3 / 3) * dy
inline = ", ".join(f"'{r}'" for r in rows)
r = kc.coefficients(kc.namelist(f"shape='mask', mask_rows={inline}, dx={dx}, dy={dy}, x0={x0}, y0={y0}",
                                "nu=0.25", "scheme='backward'"), folder)
kc.close(r["L1"] * r["f11"], I1, 1e-12, "segments: L1 f11 = I1")
kc.close(r["L2"] * r["f22"], I1, 1e-12, "segments: L2 f22 = I1")
kc.close(r["L3"] * r["f23"], I3, 1e-12, "segments: L3 f23 = I3")

# 3. ellipses against Kalker's formulas with kcreep's own coefficients
for a, b, mx, my in ((1.0, 1.0, 160, 160), (2.0, 1.0, 240, 120)):
    g = 2.0
    r = kc.coefficients(kc.namelist(f"semi_a={a}, semi_b={b}, mx={mx}, my={my}", f"g={g}, nu=0.25",
                                    "scheme='backward'"), folder)
    kc.close(r["L1"], 8 * a / (3 * r["c11"] * g), 5e-4, f"ellipse a/b={a/b:g}: L1 vs 8a/(3 C11 G)")
    kc.close(r["L2"], 8 * a / (3 * r["c22"] * g), 5e-4, f"ellipse a/b={a/b:g}: L2 vs 8a/(3 C22 G)")
    kc.close(r["L3"], math.pi * a * math.sqrt(a / b) / (4 * r["c23"] * g), 5e-4,
             f"ellipse a/b={a/b:g}: L3 vs pi a sqrt(a/b)/(4 C23 G)")
kc.finish()
