#!/usr/bin/env python3
"""Could the accurate mode (target_error = 1e-4) reach its target with fewer
or cheaper levels? (docs/accuracy.md section 6.3)

    /usr/bin/python3 lab/level_design_study.py

Uses the stored levels of six ellipses (docs/data/*levels.dat, 56 to 1024
cells across; see lab/level_noise_study.py) and asks two questions:

1. Honesty of two estimators over every design "the base levels 56-296 plus
   one or two finer levels J" the data allow. The reference of a design is
   the fit f0 + K h + L h^2 + B harmonic4 through the stored levels from 256
   cells across *without* the design's own J (at least 6 levels left, the
   finest at least 1.3 J). Estimators:
   - kcreep's (kcreep_refine_estimate.ellipse_level_estimate): the finest 8
     levels, f0 + K h + B harmonic4, t95 x SE + 0.1 |f0 - f(finest)|;
   - a weighted fit with the h^2 term, f0 + K h + L h^2 + B harmonic4,
     weights N^2 (the noise falls as 1/N, section 6.1), t95 x SE only,
     through the levels from a first level N1 = 56, 84, 112 or 148.
2. Cost: the cheapest design (one to three levels beyond 296) whose kcreep
   estimate meets the target, against the design of steps of about 15 %
   (340, 384, 448, ...) that kcreep runs. Cost model: one level of N_cells
   patch cells takes 13.7 s x (N_cells / 282,792)^1.15 (one thread, measured
   at 148-600 cells across on the unit circle before the threaded transforms).
3. Smaller order margins, along kcreep's own level sequence (56, 64, ...
   as far as the stored levels go, the fit through the finest 8 each time),
   against the fit f0 + K h + L h^2 + B harmonic4 through all stored levels
   from 224 cells across: kcreep's margin (a tenth of the extrapolation),
   that margin scaled by 56 / N_first of the window (the straight line's
   miss is about L h_first h_last, which falls with h_first), and a
   curvature margin 2 |L| h_first h_last with L from a weighted fit of
   f0 + K h + L h^2 + B harmonic4 through all levels of the run.

Needs numpy (Debian python3-numpy; /usr/bin/python3).
"""
import itertools
import math
import os
import sys

if __name__ == "__main__" and any(a in ("-h", "--help") for a in sys.argv[1:]):
    print(__doc__)
    sys.exit(0)
import numpy as np  # noqa: E402

sys.path[:0] = [os.path.join(os.path.dirname(os.path.abspath(__file__)), d) for d in (".", "../tools/maintenance", "../scripts/convergence", "../tests/calibration")]
import level_noise_study as study  # noqa: E402
from kcreep_levels import student_t95  # noqa: E402
from level_fit import fit_levels, kcreep_estimate  # noqa: E402

BASE = [56, 64, 72, 84, 96, 112, 128, 148, 172, 196, 224, 256, 296]
COEFFS = ("c11", "c22", "c23")
TARGETS = {"c11": 1e-4, "c22": 1e-4, "c23": 3e-4}
STEPS = [340, 384, 448, 512, 576, 640, 768]


def fit(levels, ns, coeff, quadratic, weighted):
    """f0, its standard error, the degrees of freedom and f at the finest level."""
    coef, se, dof, _ = fit_levels(levels, ns, coeff, quadratic=quadratic, weighted=weighted)
    return coef[0], se, dof, levels[max(ns)][coeff]


def quadratic_estimate(first):
    def estimate(levels, ns, coeff):
        f0, se, dof, _ = fit(levels, [n for n in ns if n >= first], coeff, quadratic=True, weighted=True)
        return f0, student_t95(dof) * se / abs(f0)
    return estimate


def cost(ratio, ns):
    return sum(13.7 * (math.pi / 4 * n * n * max(ratio, 1 / ratio) / 282792) ** 1.15 for n in ns)


def honesty(estimators):
    print("| estimator | designs x coefficients | bounded | error / estimate: median, 95 %, worst |")
    print("|---|---|---|---|")
    for name, estimate in estimators:
        ratios = []
        for ratio, nu in study.CASES:
            levels = study.levels_of(ratio, nu)
            fine = [n for n in sorted(levels) if n >= 340]
            for k in (1, 2):
                for jumps in itertools.combinations(fine, k):
                    rest = [n for n in sorted(levels) if n >= 256 and n not in jumps]
                    if len(rest) < 6 or max(rest) < 1.3 * max(jumps):
                        continue
                    for coeff in COEFFS:
                        reference = fit(levels, rest, coeff, quadratic=True, weighted=False)[0]
                        f0, estimate_value = estimate(levels, BASE + list(jumps), coeff)
                        ratios.append(abs(f0 / reference - 1) / estimate_value)
        q = np.quantile(ratios, [0.5, 0.95, 1.0])
        bounded = sum(r <= 1 for r in ratios)
        print(f"| {name} | {len(ratios)} | {bounded} | {q[0]:.2f}, {q[1]:.2f}, {q[2]:.2f} |")


def cheapest():
    print("\n| a/b | nu | kcreep's steps: levels beyond 296, cost | cheapest design meeting the target, cost |")
    print("|---|---|---|---|")
    for ratio, nu in study.CASES:
        levels = study.levels_of(ratio, nu)

        def meets(ns):
            return all(kcreep_estimate(levels, ns, c)[1] <= TARGETS[c] for c in COEFFS)
        steps = [n for n in STEPS if n in levels]
        ns = list(BASE)
        for n in [None] + steps:
            if n:
                ns.append(n)
            if meets(ns):
                break
        stepped = f"{ns[13:] or 'none'}, {cost(ratio, ns):.0f} s" if meets(ns) else "not within the stored levels"
        fine = [n for n in sorted(levels) if n >= 340]
        best = min(((cost(ratio, BASE + list(j)), j) for k in (0, 1, 2, 3) for j in itertools.combinations(fine, k)
                    if meets(BASE + list(j))), default=None)
        best_text = f"{list(best[1]) or 'none'}, {best[0]:.0f} s" if best else "none"
        print(f"| {ratio:g} | {nu:g} | {stepped} | {best_text} |")


SEQUENCE = [56, 64, 72, 84, 96, 112, 128, 148, 172, 196, 224, 256, 296, 340, 384, 448, 512, 576, 640, 768]


def window_estimate(margin):
    """The finest-8 straight line with t95 x SE plus margin(levels, ns, coeff, f0, finest)."""
    def estimate(levels, ns, coeff):
        f0, se, dof, finest = fit(levels, ns[-8:], coeff, quadratic=False, weighted=False)
        return f0, (student_t95(dof) * se + margin(levels, ns, coeff, f0, finest)) / abs(f0)
    return estimate


def curvature(levels, ns, coeff):
    """L of the weighted fit f0 + K h + L h^2 + B harmonic4 through the levels ns."""
    return fit_levels(levels, ns, coeff, quadratic=True, weighted=True)[0][2]


def scaled_margins():
    margins = [
        ("kcreep's: 0.1 abs(f0 - f(finest))", lambda lv, ns, c, f0, fin: 0.1 * abs(f0 - fin)),
        ("scaled: 0.1 (56 / N_first) abs(f0 - f(finest))", lambda lv, ns, c, f0, fin: 0.1 * 56 / ns[-8] * abs(f0 - fin)),
        ("curvature: 2 abs(L) h_first h_last", lambda lv, ns, c, f0, fin: 2 * abs(curvature(lv, ns, c)) / (ns[-8] * ns[-1])),
    ]
    print("\n| order margin | runs x coefficients | bounded | first level meeting 1e-4, per ellipse |")
    print("|---|---|---|---|")
    for name, margin in margins:
        estimate = window_estimate(margin)
        bounded = total = 0
        stops = []
        for ratio, nu in study.CASES:
            levels = study.levels_of(ratio, nu)
            run = [n for n in SEQUENCE if n in levels]
            reference = {c: fit(levels, [n for n in sorted(levels) if n >= 224], c, quadratic=True, weighted=False)[0]
                         for c in COEFFS}
            stop = None
            for k in range(8, len(run) + 1):
                meets = True
                for c in COEFFS:
                    f0, value = estimate(levels, run[:k], c)
                    total += 1
                    bounded += abs(f0 / reference[c] - 1) <= value
                    meets = meets and value <= TARGETS[c]
                if meets and stop is None:
                    stop = run[k - 1]
            stops.append(f"{ratio:g}: {stop or '-'}")
        print(f"| {name} | {total} | {bounded} | {', '.join(stops)} |")


def main():
    honesty([("kcreep's (finest 8, straight line, order margin)", kcreep_estimate)] +
            [(f"weighted, with h^2, from {first}", quadratic_estimate(first)) for first in (56, 84, 112, 148)])
    cheapest()
    scaled_margins()


if __name__ == "__main__":
    main()
