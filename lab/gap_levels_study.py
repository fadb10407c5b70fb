#!/usr/bin/python3
"""The measurements behind the error control of gap patches (docs/accuracy.md,
section "Patches from a gap function"): Hertzian gaps h = x^2/(2 Rx) + y^2/2
(approach 0.01, G = 1, nu = 0.25) for Rx = 0.5, 1, 2, each solved as given
(target_error = 0) on explicit square grids centred on the contact with N
cells across 2 sqrt(a b), N scaled by s = 0.96 ... 1.04 to vary the staircase.
Reference: the ellipse with Hertz's semi-axes, kcreep's ellipse error control
at target 1e-4 (its estimate is the reference's u).

  /usr/bin/python3 lab/gap_levels_study.py [--kcreep build/kcreep]

1. scatter about the first-order line through N = 16 ... 96 (circle) with the
   coefficients normalised by each grid's own contact area or by Hertz's area;
2. level sets (the fit f0 + K h, 95 % interval) against the reference;
3. one grid's estimate from coarser geometry (h: N = 24 ... 64), rules.
Needs numpy and scipy; about 10 minutes on 2 cores.
"""
import argparse
import math
import os
import sys

sys.dont_write_bytecode = True   # importing the sibling script leaves no cache behind
import tempfile



def arguments():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--kcreep", default=os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))),
                                                    "build", "kcreep"))
    return p


if __name__ == "__main__":
    ARGS = arguments().parse_args()   # --help answers before numpy and scipy load
import numpy as np  # noqa: E402

sys.path[:0] = [os.path.join(os.path.dirname(os.path.abspath(__file__)), d) for d in (".", "../tools/maintenance", "../scripts/convergence", "../tests/calibration")]
from hertz_gaps import Runner, hertz  # noqa: E402
from gap_error_calibration import fit  # noqa: E402

KEYS = ("c11", "c22", "c23")


def fit_rel(h, f):
    """f0, the relative 95 % interval and the rms residual of the fit f0 + K h."""
    f0, half, rms = fit(h, f)
    return f0, half / abs(f0), rms / abs(f0)


def level(runner, rx, n):
    """The gap solved as given with n cells across 2 sqrt(ab): own-area C's and Hertz-area C's."""
    a, b = hertz(rx, 1.0, 0.01)
    c = math.sqrt(a * b)
    d = 2 * c / n
    mx, my = math.ceil(2.6 * a / d), math.ceil(2.6 * b / d)
    x0, y0 = -(mx - 1) * d / 2, -(my - 1) * d / 2
    r = runner.run(f"&patch shape = 'gap', mx = {mx}, my = {my}, dx = {d!r}, dy = {d!r}, x0 = {x0!r}, "
                   f"y0 = {y0!r} /\n&normal rx = {rx!r}, ry = 1.0, approach = 0.01 /\n"
                   "&material g = 1, nu = 0.25 /\n&solver target_error = 0 /\n")
    out = {k: r[k] for k in KEYS}
    for k, p in (("f11", 2), ("f22", 2), ("f23", 3)):
        out["hertz_" + k] = r[k] / c ** p
    return out


def main(args):
    with tempfile.TemporaryDirectory() as work:
        runner = Runner(os.path.abspath(args.kcreep), work)
        refs = {}
        for rx in (0.5, 1.0, 2.0):
            a, b = hertz(rx, 1.0, 0.01)
            r = runner.run(f"&patch shape = 'ellipse', semi_a = {a!r}, semi_b = {b!r} /\n"
                           "&material g = 1, nu = 0.25 /\n&solver target_error = 1e-4 /\n")
            refs[rx] = {k: (r[k], r["err" + k[1:]]) for k in KEYS}

        print("## 1. scatter about f0 + K h, circle, N = 16 ... 96 (rms residual / f0, actual error of f0)\n")
        ns = [16, 20, 24, 28, 32, 36, 40, 48, 56, 64, 80, 96]
        lv = [level(runner, 1.0, n) for n in ns]
        print("| normalised by | coefficient | rms residual | f0 error |")
        print("|---|---|---|---|")
        for label, pre in (("each grid's contact area", ""), ("Hertz's area", "hertz_")):
            for k, fk in zip(KEYS, ("f11", "f22", "f23")):
                key = k if not pre else pre + fk
                f0, _, rms = fit_rel([1 / n for n in ns], [x[key] for x in lv])
                print(f"| {label} | {k.upper()} | {100 * rms:.3f} % | {100 * (f0 / refs[1.0][k][0] - 1):+.3f} % |")

        print("\n## 2. level sets (N scaled by s = 0.96 ... 1.04; 45 coefficient cases)\n")
        sets = {"16-48 (8)": [16, 20, 24, 28, 32, 36, 40, 48], "20-56 (8)": [20, 24, 28, 32, 36, 40, 48, 56],
                "24-56 (8)": [24, 28, 32, 36, 40, 44, 48, 56], "24-56 (6)": [24, 28, 32, 40, 48, 56],
                "24-56 (5)": [24, 32, 40, 48, 56], "24-64 (8)": [24, 28, 32, 36, 40, 48, 56, 64]}
        needed = sorted(set(sum(sets.values(), [])))
        rows = []
        single = []
        for rx in (0.5, 1.0, 2.0):
            for s in (0.96, 0.98, 1.0, 1.02, 1.04):
                d = {n: level(runner, rx, n * s) for n in needed}
                for name, ls in sets.items():
                    for k in KEYS:
                        f0, est, _ = fit_rel([1 / (n * s) for n in ls], [d[n][k] for n in ls])
                        ref, u = refs[rx][k]
                        rows.append((name, abs(f0 / ref - 1), est, u))
            for n in range(24, 68, 4):
                c = [level(runner, rx, m) for m in (n, n / 1.5, n / 2)]
                for k in KEYS:
                    single.append((abs(c[0][k] / refs[rx][k][0] - 1), abs(c[0][k] - c[2][k]) / c[0][k],
                                   abs(c[0][k] - c[1][k]) / c[0][k]))
        print("| levels | cases | bounded | bounded allowing u | median error | median estimate |")
        print("|---|---|---|---|---|---|")
        for name in sets:
            r = [x for x in rows if x[0] == name]
            print(f"| {name} | {len(r)} | {sum(e <= est for _, e, est, _ in r)} | "
                  f"{sum(e <= est + u for _, e, est, u in r)} | {100 * np.median([x[1] for x in r]):.3f} % | "
                  f"{100 * np.median([x[2] for x in r]):.3f} % |")

        print("\n## 3. one grid: estimate rules (N = 24 ... 64, 99 coefficient cases)\n")
        rules = {"2 |C(h) - C(2h)|": lambda d2, d15: 2 * d2, "3 |C(h) - C(2h)|": lambda d2, d15: 3 * d2,
                 "max(2 |C(h) - C(2h)|, 4 |C(h) - C(1.5h)|)": lambda d2, d15: max(2 * d2, 4 * d15),
                 "3 max(|C(h) - C(2h)|, 2 |C(h) - C(1.5h)|) (kcreep)": lambda d2, d15: 3 * max(d2, 2 * d15)}
        print("| rule (relative to C(h)) | bounded | median estimate / error |")
        print("|---|---|---|")
        for name, rule in rules.items():
            ests = [rule(d2, d15) for _, d2, d15 in single]
            errs = [e for e, _, _ in single]
            print(f"| {name} | {sum(e <= x for e, x in zip(errs, ests))} of {len(errs)} | "
                  f"{np.median([x / max(e, 1e-12) for e, x in zip(errs, ests)]):.1f} |")


if __name__ == "__main__":
    main(ARGS)
