"""Symmetry, mirror invariance, scaling and nu = 0 decoupling.

These are exact properties of the continuous problem that the discrete
one keeps up to round-off, so tolerances are round-off sized: 1e-10
relative (measured differences are below 1e-13)."""
import kctest as kc

folder = kc.setup()
# an asymmetric, non-convex patch (rows in increasing y)
rows = ["..####......",
        ".#######....",
        "##########..",
        "###########.",
        "....########",
        ".....#######",
        "###..######.",
        "##########..",
        ".########...",
        "...####....."]


def mask_patch(rows, dx=0.1, dy=0.1, x0=None, y0=None):
    my, mx = len(rows), len(rows[0])
    x0 = -(mx - 1) * dx / 2 if x0 is None else x0
    y0 = -(my - 1) * dy / 2 if y0 is None else y0
    inline = ", ".join(f"'{r}'" for r in rows)
    return f"shape='mask', mask_rows={inline}, dx={dx}, dy={dy}, x0={x0}, y0={y0}"


names = ["f11", "f12", "f13", "f21", "f22", "f23", "f31", "f32", "f33"]
for scheme in ("collocation", "backward"):
    # ellipse: symmetric in y, so no coupling between (xi) and (eta, phi)
    e = kc.coefficients(kc.namelist("semi_a=1.5, semi_b=1, mx=30, my=20", "nu=0.3", f"scheme='{scheme}'"), folder)
    for name in ("f12", "f13", "f21", "f31"):
        kc.small(e[name], e["f11"], 1e-10, f"{scheme} ellipse cross term {name} vanishes")

    # mirror in y: f11, f22, f23, f32, f33 unchanged; f12, f13, f21, f31 change sign
    p = kc.coefficients(kc.namelist(mask_patch(rows), "nu=0.3", f"scheme='{scheme}'"), folder)
    m = kc.coefficients(kc.namelist(mask_patch(rows[::-1]), "nu=0.3", f"scheme='{scheme}'"), folder)
    for name in names:
        sign = -1 if name in ("f12", "f13", "f21", "f31") else 1
        kc.check(abs(m[name] - sign * p[name]) <= 1e-10 * abs(p["f11"]),
                 f"{scheme} mirror in y: {name} {p[name]:.6e} -> {m[name]:.6e} (sign {sign:+d})")
    kc.check(abs(p["f12"]) > 1e-3 * p["f11"], f"{scheme} asymmetric patch at nu=0.3 couples x and y (f12 = {p['f12']:.3e})")

    # scaling: f ~ G; f11, f22 ~ s^2, f23 ~ s^3, f33 ~ s^4; normalised values unchanged
    base = kc.coefficients(kc.namelist(mask_patch(rows), "g=1, nu=0.3", f"scheme='{scheme}'"), folder)
    for g in (1e-3, 1e12):
        r = kc.coefficients(kc.namelist(mask_patch(rows), f"g={g}, nu=0.3", f"scheme='{scheme}'"), folder)
        for name in names:
            kc.check(abs(r[name] - g * base[name]) <= 1e-10 * g * abs(base["f11"]) * 10,
                     f"{scheme} g = {g:g} scales {name}")
    power = {"f11": 2, "f12": 2, "f21": 2, "f22": 2, "f13": 3, "f23": 3, "f31": 3, "f32": 3, "f33": 4}
    for s in (1e-6, 1e3):
        r = kc.coefficients(kc.namelist(mask_patch(rows, dx=0.1 * s, dy=0.1 * s), "nu=0.3", f"scheme='{scheme}'"), folder)
        for name in names:
            scale = s ** power[name]
            ref = abs(base["f11"]) * 0.6 ** (power[name] - 2)   # a size of the typical entry
            kc.check(abs(r[name] - scale * base[name]) <= 1e-10 * scale * ref * 10,
                     f"{scheme} length x {s:g} scales {name} by s^{power[name]}")
        for name in ("c11", "c22", "c23"):
            kc.close(r[name], base[name], 1e-10, f"{scheme} length x {s:g}: {name} unchanged")

    # nu = 0 decouples x and y: no Fx from eta, no Fy from xi, even on an asymmetric patch
    z = kc.coefficients(kc.namelist(mask_patch(rows), "nu=0", f"scheme='{scheme}'"), folder)
    kc.small(z["f12"], z["f11"], 1e-12, f"{scheme} nu=0: f12 vanishes")
    kc.small(z["f21"], z["f11"], 1e-12, f"{scheme} nu=0: f21 vanishes")
    kc.check(abs(z["f13"]) > 1e-3 * z["f11"] * 0.6, f"{scheme} nu=0: spin still gives Fx on an asymmetric patch ({z['f13']:.3e})")
kc.finish()
