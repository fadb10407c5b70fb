#!/usr/bin/python3
"""Is the error estimate of a patch from a gap function honest? (docs/accuracy.md,
section "Patches from a gap function")

Hertzian gaps h = x^2/(2 Rx) + y^2/(2 Ry) (Ry = 1, approach 0.01, G = 1) for
Rx/Ry = 0.2, 0.5, 1, 2, 5 and nu = 0, 0.25, 0.5: kcreep's default run (levels
of finer geometry, target 1e-3) and the single grid (target_error = 0, the
automatic grid of cells_across = 60) against the ellipse with Hertz's
semi-axes solved by kcreep's ellipse error control at target 1e-4 (its own
estimate is the reference's uncertainty u).

Non-elliptic gaps: the worn wheel on rail (input/wheel_rail.gap; the reference
evaluates its profile functions exactly on finer grids) and CONTACT's kidney
sample (its gap per element, resampled bicubically as kcreep does): reference
the first-order fit through levels of 96 to 192 cells across the contact
area's equivalent diameter (each solved as given), u its 95 % interval.

  /usr/bin/python3 lab/gap_error_calibration.py [--kcreep build/kcreep]
      [--samples ../shared/contact-samples] [--out docs/data/gap_error_calibration.dat]
      [--quick]   (Rx/Ry = 1, 2 at nu = 0.25 and the wheel only: a smoke run)

Needs numpy and scipy. Prints a markdown table of estimate against error.
The Hertzian part is the test calibration_gap_levels
(tests/calibration/test_gap_levels.py), which this study shares its runner with.
"""
import argparse
import math
import os
import subprocess
import sys

sys.dont_write_bytecode = True   # importing the sibling script leaves no cache behind
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)


def arguments():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--kcreep", default=os.path.join(ROOT, "build", "kcreep"))
    p.add_argument("--samples", default=os.path.join(ROOT, "..", "shared", "contact-samples"))
    p.add_argument("--out", default=None)
    p.add_argument("--quick", action="store_true")
    return p


if __name__ == "__main__":
    ARGS = arguments().parse_args()   # --help answers before numpy and scipy load
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.join(ROOT, "python"))
from kcreep import contact_inp  # noqa: E402  (standard library only)
sys.path[:0] = [HERE, os.path.join(ROOT, "tools", "maintenance")]
sys.path.insert(0, os.path.join(ROOT, "scripts"))   # wheel_rail_gap.py, the profiles of input/wheel_rail.gap
from kcreep_levels import student_t95  # noqa: E402  (standard library only)
sys.path.insert(0, os.path.join(ROOT, "tests", "calibration"))
from hertz_gaps import Runner, hertz  # noqa: E402  (the calibration tests' runner)

KEYS = ("c11", "c22", "c23")


def fit(h, f):
    """First-order least squares f0 + K h: f0, its 95 % interval (absolute) and
    the rms residual."""
    h, f = np.asarray(h, float), np.asarray(f, float)
    m = len(h)
    a = np.vstack([np.ones(m), h]).T
    c = np.linalg.lstsq(a, f, rcond=None)[0]
    r = f - a @ c
    hm = h.mean()
    se = math.sqrt((r @ r) / (m - 2) * (1 / m + hm ** 2 / ((h - hm) ** 2).sum()))
    return c[0], student_t95(m - 2) * se, math.sqrt(r @ r / m)


def keys_weights(t):
    return np.array([((-t + 2) * t - 1) * t / 2, ((3 * t - 5) * t * t + 2) / 2,
                     ((-3 * t + 4) * t + 1) * t / 2, (t - 1) * t * t / 2])


def resample(h, dx, dy, x0, y0, xs, ys):
    """kcreep_gap gap_resampled: Catmull-Rom, edges continued quadratically."""
    mx, my = h.shape
    g = np.empty((mx + 4, my + 4))
    g[2:-2, 2:-2] = h
    for d in (1, 2):   # quadratic continuation in x, then y
        g[2 - d, 2:-2] = h[0] * (d + 1) * (d + 2) / 2 - h[1] * d * (d + 2) + h[2] * d * (d + 1) / 2
        g[mx + 1 + d, 2:-2] = h[-1] * (d + 1) * (d + 2) / 2 - h[-2] * d * (d + 2) + h[-3] * d * (d + 1) / 2
    for d in (1, 2):
        g[:, 2 - d] = g[:, 2] * (d + 1) * (d + 2) / 2 - g[:, 3] * d * (d + 2) + g[:, 4] * d * (d + 1) / 2
        g[:, my + 1 + d] = g[:, my + 1] * (d + 1) * (d + 2) / 2 - g[:, my] * d * (d + 2) + g[:, my - 1] * d * (d + 1) / 2
    out = np.empty((len(xs), len(ys)))
    sx = (np.asarray(xs) - x0) / dx + 1
    sy = (np.asarray(ys) - y0) / dy + 1
    ix = np.clip(np.floor(sx).astype(int), 0, mx)
    iy = np.clip(np.floor(sy).astype(int), 0, my)
    wx = [keys_weights(min(max(s - i, 0.0), 1.0)) for s, i in zip(sx, ix)]
    wy = [keys_weights(min(max(s - i, 0.0), 1.0)) for s, i in zip(sy, iy)]
    for j, (jj, wj) in enumerate(zip(iy, wy)):
        rows = g[:, jj:jj + 4] @ wj          # cells jj-1 .. jj+2 (cell c is g[c + 1])
        for i, (ii, wi) in enumerate(zip(ix, wx)):
            out[i, j] = rows[ii:ii + 4] @ wi
    return out


def gap_file_text(values, dx, dy, x0, y0):
    mx, my = values.shape
    lines = [f"{mx} {my} {dx!r} {dy!r} {x0!r} {y0!r}"]
    for j in range(my):
        lines.append(" ".join(f"{v:.14e}" for v in values[:, j]))
    return "\n".join(lines) + "\n"


def hertz_cases(runner, quick):
    ratios = [1, 2] if quick else [0.2, 0.5, 1, 2, 5]
    nus = [0.25] if quick else [0, 0.25, 0.5]
    rows = []
    for ratio in ratios:
        for nu in nus:
            rx, ry, delta = float(ratio), 1.0, 0.01
            a, b = hertz(rx, ry, delta)
            common = f"&material g = 1, nu = {nu} /\n"
            ref = runner.run(f"&patch shape = 'ellipse', semi_a = {a!r}, semi_b = {b!r} /\n" + common +
                             "&solver target_error = 1e-4 /\n")
            gap = f"&patch shape = 'gap' /\n&normal rx = {rx!r}, ry = {ry!r}, approach = {delta!r} /\n" + common
            dflt = runner.run(gap)
            single = runner.run(gap + "&solver target_error = 0 /\n")
            for label, r in (("levels (default)", dflt), ("one grid, cells_across 60", single)):
                for i, k in enumerate(KEYS):
                    rows.append(dict(case=f"hertz Rx/Ry={ratio:g} nu={nu:g} a/b={a / b:.3f}", estimator=label,
                                     coefficient=k.upper(), value=r[k], ref=ref[k],
                                     u=ref["err" + k[1:]] * abs(ref[k]), estimate=r["err" + k[1:]],
                                     area_error=(r["c"] / math.sqrt(a * b)) ** 2 - 1, verdict=r["verdict"],
                                     wall=r["wall"]))
    return rows


def level_reference(runner, name, make_gap, diameter, extent, common, levels):
    """First-order fit through the levels N (cells across the equivalent diameter)."""
    hs, cs = [], {k: [] for k in KEYS}
    for n in levels:
        d = diameter / n
        mx = int(math.floor((extent[1] - extent[0]) / d + 1e-9))
        my = int(math.floor((extent[3] - extent[2]) / d + 1e-9))
        x0 = (extent[0] + extent[1]) / 2 - (mx - 1) * d / 2
        y0 = (extent[2] + extent[3]) / 2 - (my - 1) * d / 2
        xs, ys = x0 + d * np.arange(mx), y0 + d * np.arange(my)
        text = gap_file_text(make_gap(xs, ys), d, d, x0, y0)
        r = runner.run(f"&patch shape = 'gap' /\n&normal gap_file = '{name}_level.gap', {common}/\n"
                       "&solver target_error = 0 /\n", files={f"{name}_level.gap": text})
        hs.append(1 / n)
        for k in KEYS:
            cs[k].append(r[k])
    return {k: fit(hs, cs[k]) for k in KEYS}


def nonelliptic_cases(runner, samples, quick):
    rows = []
    # the worn wheel on rail: the profiles of scripts/wheel_rail_gap.py, exactly
    import importlib
    wr = importlib.import_module("wheel_rail_gap")
    dmin = min(wr.lateral(wr.Y1 + k * 1e-3) for k in range(-20000, 20001))
    lateral = np.vectorize(wr.lateral)

    def wheel(xs, ys):
        return (lateral(ys) - dmin)[None, :] + (np.asarray(xs) ** 2 / (2 * wr.R_WHEEL))[:, None]

    gap_path = os.path.join(ROOT, "input", "wheel_rail.gap")
    load = "normal_force = 80000.0, e1 = 210000.0, nu1 = 0.28, e2 = 210000.0, nu2 = 0.28 "
    cases = [("wheel_rail", wheel, open(gap_path).read(), load, (-8.0, 8.0, -11.0, 13.0))]
    if samples and not quick:
        values = contact_inp.gap_values(os.path.join(samples, "kidney_nu25.inp"), 36 * 60)
        dx = 1 / 24
        h = np.array([float(v) for v in values]).reshape(60, 36).T
        x0, y0 = -0.625 + dx / 2, -1.25 + dx / 2

        def kidney(xs, ys, h=h, dx=dx, x0=x0, y0=y0):
            return resample(h, dx, dx, x0, y0, xs, ys)

        cases.append(("kidney", kidney, gap_file_text(h, dx, dx, x0, y0),
                      "approach = 0.2 /\n&material g = 82000, nu = 0.25 ", (-0.625, 0.875, -1.25, 1.25)))
    for name, make_gap, text, common, extent in cases:
        files = {f"{name}.gap": text}
        base = f"&patch shape = 'gap' /\n&normal gap_file = '{name}.gap', {common}/\n"
        dflt = runner.run(base, files=files)
        coll = runner.run(base + "&solver scheme = 'collocation', alpha = 0.5 /\n", files=files)
        single = runner.run(base + "&solver target_error = 0 /\n", files=files)
        diameter = 2 * dflt["c"]
        ref = level_reference(runner, name, make_gap, diameter, extent, common,
                              [96, 128, 160] if quick else [96, 112, 128, 144, 160, 192])
        for label, r in (("levels (default)", dflt), ("levels, collocation 0.5", coll),
                         ("one grid (the file's)", single)):
            for k in KEYS:
                rows.append(dict(case=name, estimator=label, coefficient=k.upper(), value=r[k], ref=ref[k][0],
                                 u=ref[k][1], estimate=r["err" + k[1:]], area_error=float("nan"),
                                 verdict=r["verdict"], wall=r["wall"]))
    return rows


def main(args):
    samples = args.samples if os.path.isdir(args.samples) else None
    with tempfile.TemporaryDirectory() as work:
        runner = Runner(os.path.abspath(args.kcreep), work)
        rows = hertz_cases(runner, args.quick)
        rows += nonelliptic_cases(runner, samples, args.quick)
    for r in rows:
        r["error"] = abs(r["value"] / r["ref"] - 1)
        r["bounded"] = r["error"] <= r["estimate"]
        r["bounded_u"] = r["error"] <= r["estimate"] + abs(r["u"] / r["ref"])
    if args.out:
        with open(args.out, "w") as f:
            f.write("# lab/gap_error_calibration.py: estimate against error of patches from a gap function\n")
            f.write("# case | estimator | coefficient value ref u_ref(abs) estimate(rel) error(rel) "
                    "area_error(rel, Hertz) verdict wall_s\n")
            for r in rows:
                f.write(f"{r['case']} | {r['estimator']} | {r['coefficient']} {r['value']:.6f} {r['ref']:.6f} "
                        f"{r['u']:.2e} {r['estimate']:.3e} {r['error']:.3e} {r['area_error']:.3e} "
                        f"{r['verdict']} {r['wall']:.2f}\n")
    print("| gaps | estimator | coefficient | cases | bounded | bounded allowing u | median error | "
          "worst error | median estimate |")
    print("|---|---|---|---|---|---|---|---|---|")
    for group in ("hertz", "non-elliptic"):
        sel = [r for r in rows if r["case"].startswith("hertz") == (group == "hertz")]
        for est in dict.fromkeys(r["estimator"] for r in sel):
            for k in ("C11", "C22", "C23"):
                s = [r for r in sel if r["estimator"] == est and r["coefficient"] == k]
                if not s:
                    continue
                err = [r["error"] for r in s]
                print(f"| {group} | {est} | {k} | {len(s)} | {sum(r['bounded'] for r in s)} | "
                      f"{sum(r['bounded_u'] for r in s)} | {100 * np.median(err):.3f} % | {100 * max(err):.3f} % | "
                      f"{100 * np.median([r['estimate'] for r in s]):.3f} % |")
    print()
    print("| case | estimator | C11 err / est | C22 err / est | C23 err / est | verdict | wall s |")
    print("|---|---|---|---|---|---|---|")
    seen = {}
    for r in rows:
        seen.setdefault((r["case"], r["estimator"]), []).append(r)
    for (case, est), s in seen.items():
        cells = " | ".join(f"{100 * r['error']:.3f} / {100 * r['estimate']:.3f} %" for r in s)
        print(f"| {case} | {est} | {cells} | {s[0]['verdict']} | {s[0]['wall']:.2f} |")
    hz = [r for r in rows if r["case"].startswith("hertz") and r["estimator"].startswith("levels")
          and r["coefficient"] == "C11"]
    if hz:
        ae = [abs(r["area_error"]) for r in hz]
        print(f"\ncontact area of the default run against pi a b (Hertz): median {100 * np.median(ae):.3f} %, "
              f"worst {100 * max(ae):.3f} %")


if __name__ == "__main__":
    main(ARGS)
