"""shape='ellipse' and the same cells given as a mask (file and inline)
give the same f's: the same cells on the same grid must assemble the same
system, so the tolerance is round-off (1e-12 relative to f11)."""
import kctest as kc

folder = kc.setup()
a, b, mx, my = 1.3, 0.9, 26, 18
dx, dy = 2 * a / mx, 2 * b / my
x0, y0 = -a + dx / 2, -b + dy / 2
rows = []
for iy in range(my):
    y = y0 + iy * dy
    rows.append("".join("#" if ((x0 + ix * dx) / a) ** 2 + (y / b) ** 2 <= 1 else "." for ix in range(mx)))
mask_file = f"{mx} {my} {dx!r} {dy!r} {x0!r} {y0!r}\n" + "\n".join(rows) + "\n"
inline = ", ".join(f"'{r}'" for r in rows)
names = ["f11", "f12", "f13", "f21", "f22", "f23", "f31", "f32", "f33"]
for scheme in ("collocation", "backward"):
    solver = f"{kc.scheme_setting(scheme, 0.4)}"
    e = kc.coefficients(kc.namelist(f"semi_a={a}, semi_b={b}, mx={mx}, my={my}", "nu=0.2", solver), folder, "e")
    _, _, _, t = kc.run(kc.namelist("shape='mask', mask_file='ell.mask'", "nu=0.2", solver), folder, "f",
                        files={"ell.mask": mask_file})
    f = t[0]
    i = kc.coefficients(kc.namelist(f"shape='mask', mask_rows={inline}, dx={dx!r}, dy={dy!r}, x0={x0!r}, y0={y0!r}",
                                    "nu=0.2", solver), folder, "i")
    kc.check(e["n"] == f["n"] == i["n"], f"{scheme}: same number of cells ({e['n']:.0f}, {f['n']:.0f}, {i['n']:.0f})")
    for name in names:
        kc.check(abs(f[name] - e[name]) <= 1e-12 * e["f11"], f"{scheme} mask file = ellipse: {name}")
        kc.check(abs(i[name] - e[name]) <= 1e-12 * e["f11"], f"{scheme} inline mask = ellipse: {name}")
    kc.check(kc.isnan(f["klt11"]) and not kc.isnan(e["klt11"]), f"{scheme}: Kalker columns only for the ellipse")
    # mask '1'/'0' characters mean the same as '#'/'.'
    rows10 = [r.replace("#", "1").replace(".", "0") for r in rows]
    j = kc.coefficients(kc.namelist("shape='mask', mask_rows=" + ", ".join(f"'{r}'" for r in rows10) +
                                    f", dx={dx!r}, dy={dy!r}, x0={x0!r}, y0={y0!r}", "nu=0.2", solver), folder, "j")
    kc.check(j["f23"] == i["f23"], f"{scheme}: '1'/'0' mask = '#'/'.' mask")
kc.finish()
