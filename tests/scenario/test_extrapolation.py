"""&solver extrapolate: the levels are the right meshes, the limit is the
Richardson formula applied to them, and the two schemes' limits agree
within their error estimates.

Measured (unit circle, nu = 0.25, base 10 x 10, 3 levels 10/20/40, each
level normalised by its staircase area): collocation C11 -> 4.1278 +- 0.0076,
C22 -> 3.6763 +- 0.021, C23 -> 1.4672 +- 0.016; backward C11 -> 4.1231 +-
0.016, C22 -> 3.6741 +- 0.0086, C23 -> 1.4666 +- 0.0013. The limits differ
by less than the sum of the estimates. Reference: the 20/40/80 limits of
both schemes (scripts/convergence/richardson.py on docs/data/sweep_n.dat, @area
rows) agree on C11 = 4.0965, C22 = 3.661, C23 = 1.4665 to 0.07 %; the
10/20/40 limits are 0.7 % (C11) off it while the 40 x 40 level is 3.5 %
(collocation) and 1.8 % (backward, raw) off: the check asks for at least a
factor 2. (The estimate does not cover that 0.7 %: docs/convergence.md.)"""
import math
import os

import kctest as kc

REFERENCE = {"11": 4.0965, "22": 3.661, "23": 1.4665}
folder = kc.setup()
circle = "semi_a=1, semi_b=1, mx=10, my=10"
rows = {}
for scheme in ("collocation", "backward"):
    s = f"scheme='{scheme}', extrapolate=.true."
    code, out, err, t = kc.run(kc.namelist(circle, "nu=0.25", s), folder, f"ext_{scheme}")
    rows[scheme] = t[0]
    kc.check(t[0]["mx"] == 40 and t[0]["my"] == 40, f"{scheme}: the row is the finest level (40 x 40)")
    kc.check("extrapolated" in out, f"{scheme}: the summary prints the extrapolated values")

# the levels are exactly the direct runs, and the limit is Richardson on them
direct = {m: kc.coefficients(kc.namelist(f"semi_a=1, semi_b=1, mx={m}, my={m}", "nu=0.25"), folder, f"d{m}")
          for m in (10, 20, 40)}
ext = rows["collocation"]
for coef in ("c11", "c22", "c23"):
    kc.close(ext[coef], direct[40][coef], 1e-12, f"finest level {coef} = direct 40 x 40 run")
    # ellipse levels are normalised by the staircase area: C * (pi ab / (n dx dy))^(1 or 3/2)
    power = 1.5 if coef == "c23" else 1.0
    f = [direct[m][coef] * (math.pi * m * m / (4 * direct[m]["n"]))**power for m in (10, 20, 40)]
    p = math.log2((f[1] - f[0]) / (f[2] - f[1]))
    if not 0.5 <= p <= 3:
        p = 1.0
    limit = f[2] + (f[2] - f[1]) / (2**p - 1)
    kc.close(ext["ext" + coef[1:]], limit, 1e-10, f"ext{coef[1:]} is the Richardson limit of 10/20/40 (p = {p:.3f})")
    kc.close(ext["extp" + coef[1:]], p, 2e-3, f"extp{coef[1:]} is the order used")

# the two schemes converge to the same limit: they must agree within their estimates
for coef in ("11", "22", "23"):
    a, b = rows["collocation"], rows["backward"]
    gap = abs(a["ext" + coef] - b["ext" + coef])
    bound = a["exterr" + coef] + b["exterr" + coef]
    kc.check(gap <= bound, f"C{coef}: collocation {a['ext' + coef]:.4f} and backward {b['ext' + coef]:.4f} "
             f"differ by {gap:.4f} <= sum of estimates {bound:.4f}")
    for scheme in ("collocation", "backward"):
        r = rows[scheme]
        kc.check(abs(r["ext" + coef] - REFERENCE[coef]) < abs(r["c" + coef] - REFERENCE[coef]) / 2,
                 f"C{coef} {scheme}: the limit {r['ext' + coef]:.4f} is at least twice as close to the 20/40/80 "
                 f"reference {REFERENCE[coef]} as the finest level {r['c' + coef]:.4f}")

# without extrapolate the columns are NaN
plain = direct[10]
kc.check(all(kc.isnan(plain[c]) for c in ("ext11", "exterr11", "extp11")), "no extrapolate: ext columns are NaN")

# a mask is refined by splitting each cell: level 2 of a mask = the split mask run directly
rows_mask = ["0110", "1111", "1111", "0110"]
rows_split = [''.join(ch * 2 for ch in r) for r in rows_mask for _ in range(2)]
mask_nml = lambda rws, d, x0, extra: kc.namelist(
    "shape='mask', mask_rows=" + ", ".join(f"'{r}'" for r in rws) + f", dx={d}, dy={d}, x0={x0}, y0={x0}",
    "nu=0.3", extra)
m2 = kc.run(mask_nml(rows_mask, 0.5, -0.75, "extrapolate=.true., extrapolate_levels=2"), folder, "mask_ext")[3][0]
split = kc.coefficients(mask_nml(rows_split, 0.25, -0.875, ""), folder, "mask_split")
for coef in ("c11", "c22", "c23", "f12", "f13"):
    kc.check(abs(m2[coef] - split[coef]) <= 1e-12 * abs(split["c11"]),
             f"mask level 2 {coef} = the split mask ({m2[coef]:.10g} vs {split[coef]:.10g})")
kc.check(m2["extp11"] == 1.0, "two levels: first order is used")

# bad input
for bad, word in (("extrapolate=.true., extrapolate_levels=4", "extrapolate_levels"),
                  ("extrapolate=.true., refine_ratio=1", "refine_ratio")):
    code, out, err, t = kc.run(kc.namelist(circle, "", bad), folder, "bad", expect_ok=False)
    kc.check(code == 2 and word in err and len(err.strip().splitlines()) == 1,
             f"{bad}: exit 2, one line naming {word} ({err.strip()})")
    kc.check(not os.path.exists(os.path.join(folder, "bad.tab")), f"{bad}: no table written")
kc.finish()
