"""The collocation scheme's degenerate and nonphysical settings are
detected and said, not printed silently.

alpha = 0 on a patch symmetric in x: the discrete operator is odd in x,
f11 = f22 = 0 up to round-off, the traction is antisymmetric (coherence 0).
On such a patch f11, f22, f33 are odd in alpha and f23, f32 are even (the
operator obeys A(-alpha) = -Q A(alpha) Q with Q = diag(-P, P), P the x
mirror, and the spin right-hand side flips with it); round-off tolerance
1e-10."""
import kctest as kc

folder = kc.setup()
patch = "semi_a=1, semi_b=1, mx=24, my=24"
ref = kc.coefficients(kc.namelist(patch, "nu=0.25", "alpha=0.5"), folder, "p")
code, out, err, t = kc.run(kc.namelist(patch, "nu=0.25", "alpha=0"), folder, "zero")
zero = t[0]
kc.check(code == 0, "alpha = 0 still writes its row")
kc.small(zero["f11"], ref["f11"], 1e-10, "alpha = 0: f11 vanishes")
kc.small(zero["f22"], ref["f22"], 1e-10, "alpha = 0: f22 vanishes")
kc.check("degenerate" in zero["verdict"], f"alpha = 0: verdict says degenerate ({zero['verdict']})")
kc.check("warning" in err and "alpha > 0" in err, "alpha = 0: a warning on stderr names the remedy")
kc.check("WARNING" in open(f"{folder}/zero.tab").read(), "alpha = 0: the table carries the warning")

neg = kc.run(kc.namelist(patch, "nu=0.25", "alpha=-0.5"), folder, "neg")[3][0]
for name in ("f11", "f22", "f33"):
    kc.check(abs(neg[name] + ref[name]) <= 1e-10 * abs(ref["f11"]), f"odd in alpha: {name}(-0.5) = -{name}(0.5)")
for name in ("f23", "f32"):
    kc.check(abs(neg[name] - ref[name]) <= 1e-10 * abs(ref["f11"]), f"even in alpha: {name}(-0.5) = {name}(0.5)")
kc.check("nonphysical" in neg["verdict"], f"alpha < 0: verdict says nonphysical ({neg['verdict']})")
kc.check(ref["verdict"] == "ok", "alpha = 0.5: verdict ok")

# elongated cells make the collocation traction oscillate: flagged, with the remedy
code, out, err, t = kc.run(kc.namelist("semi_a=5, semi_b=1, mx=40, my=40", "nu=0.25", "alpha=0.5"), folder, "long")
kc.check("degenerate" in t[0]["verdict"] and "elongated" in err, f"dx/dy = 5 collocation: flagged ({t[0]['verdict']})")
back = kc.run(kc.namelist("semi_a=5, semi_b=1, mx=40, my=40", "nu=0.25", "scheme='backward'"), folder, "longb")[3][0]
kc.check(back["verdict"] == "ok", "dx/dy = 5 backward: ok")
kc.finish()
