"""&solver refine: the four modes solve the same system and must agree.

Measured on the 30 x 30 unit circle (nu = 0.25, alpha = 0.5): berr 7.3e-17
(auto, never: no refinement needed, below 100 eps), 3.5e-17 (always),
7.3e-17 (lapack, dgesvx with equilibration); C11, C22, C23 agree to 4e-16
relative. Tolerances: 1e-12 on the coefficients, 1e-15 on berr."""
import kctest as kc

folder = kc.setup()
patch = "semi_a=1, semi_b=1, mx=30, my=30"
rows, outs = {}, {}
for mode in ("auto", "always", "never", "lapack"):
    code, out, err, table = kc.run(kc.namelist(patch, "nu=0.25", f"alpha=0.5, method='dense', refine='{mode}'"), folder, mode)
    rows[mode], outs[mode] = table[0], out
    kc.check(table[0]["verdict"] == "ok", f"refine = {mode}: verdict ok")
    kc.check(table[0]["berr"] <= 1e-15, f"refine = {mode}: berr {table[0]['berr']:.1e} <= 1e-15")
for mode in ("always", "never", "lapack"):
    for c in ("c11", "c22", "c23"):
        kc.close(rows[mode][c], rows["auto"][c], 1e-12, f"refine = {mode}: {c} as with auto")
kc.check("refine = always (refined)" in outs["always"], "always: the summary says it refined")
kc.check("refine = never (not refined)" in outs["never"], "never: the summary says it did not refine")
kc.check("refine = auto (not refined)" in outs["auto"], "auto: no refinement when berr is at round-off already")
code, out, err, _ = kc.run(kc.namelist(patch, "", "refine='sometimes'"), folder, "bad", expect_ok=False)
kc.check(code == 2 and "&solver refine = 'sometimes' (allowed: 'auto', 'always', 'never', 'lapack')" in err,
         f"unknown refine mode: {err.strip()}")
kc.finish()
