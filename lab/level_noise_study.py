#!/usr/bin/env python3
"""What limits the accurate mode (target_error = 1e-4): the ellipse levels
against references from grids of up to 1024-2048 cells across
(docs/accuracy.md section 6, the figure lab/figures/level_noise.png; --figure lab/figures/level_noise.png redraws it, default build/figures/).

    /usr/bin/python3 lab/level_noise_study.py [--no-figure | --figure FILE]

Data (all stored normalised by the staircase area, as kcreep_levels.ellipse_level
gives them): tools/maintenance/data/kalker_refined_levels.dat (56 to 196-256 cells across),
lab/data/independent_reference_levels.dat (136 to 384) and
tools/maintenance/data/fine_reference_levels.dat (256 to 1024, the unit circle to 2048;
lab/independent_check.py --cache ... computes it). Every level is referred
to the ellipse by the staircase's second moments (kcreep_levels.refer_to_ellipse).

For each ellipse and coefficient the levels from 56 cells across are fitted by
    f0 + K h + L h^2 + B harmonic4        (h = 1/N, N cells across the shorter axis)
and printed are: L / f0 (the curvature that a straight line through the levels
misses by about L h1 h2), the rms residual in bands of N (the staircase's
level-to-level noise that no smooth term takes out), and what the straight line
f0 + K h + B harmonic4 through the accurate mode's levels (112 to 296 across)
misses f0 by. The figure shows the residuals against N. Needs numpy and
matplotlib (Debian: python3-numpy, python3-matplotlib; /usr/bin/python3).
"""
import argparse
import math
import os
import sys

if __name__ == "__main__" and any(a in ("-h", "--help") for a in sys.argv[1:]):
    print("usage: lab/level_noise_study.py [options]\n" + __doc__)
    sys.exit(0)
import numpy as np  # noqa: E402

sys.path[:0] = [os.path.join(os.path.dirname(os.path.abspath(__file__)), d) for d in (".", "../tools/maintenance", "../scripts/convergence", "../tests/calibration")]
import kcreep_levels as K  # noqa: E402
from level_fit import fit_levels  # noqa: E402

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
DATA = os.path.join(ROOT, "docs", "data")
def data_file(name):
    """The study's own data in lab/data, the refined table's levels in tools/maintenance/data."""
    own = os.path.join(os.path.dirname(os.path.abspath(__file__)), "data", name)
    if os.path.exists(own):
        return own
    tool = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tools", "maintenance", "data", name)
    return tool if os.path.exists(tool) else os.path.join(DATA, name)
FILES = [data_file(f) for f in ("kalker_refined_levels.dat", "independent_reference_levels.dat",
                                         "fine_reference_levels.dat")]
FIGURE = os.path.join(ROOT, "build", "figures", "level_noise.png")  # --figure lab/figures/level_noise.png for the docs
CASES = [(1.0, 0.25), (1.0, 0.5), (2.0, 0.25), (0.5, 0.25), (4.0, 0.25), (0.25, 0.25)]
BANDS = [(56, 100), (100, 200), (200, 400), (400, 2100)]
#: the levels of an accurate-mode run of the unit circle (kcreep_error_run: the finest 8 of 56, 64, ... 296)
ACCURATE_WINDOW = [112, 128, 148, 172, 196, 224, 256, 296]


def levels_of(ratio, nu):
    """{N: level referred to the ellipse} from every levels file, N >= 56."""
    merged = {}
    for path in FILES:
        merged.update(K.read_level_file(path).get((ratio, nu), {}))
    slopes = K.table_slopes(ratio, nu)
    return {n: K.refer_to_ellipse(ratio, nu, merged[n], slopes) for n in sorted(merged) if n >= 56}


def fit(levels, ns, coeff, quadratic):
    """Coefficients (f0, K, [L,] B) of the least-squares fit through the levels ns."""
    return fit_levels(levels, ns, coeff, quadratic=quadratic)[0]


def model(coef, n, harmonic4, quadratic):
    h = 1.0 / n
    return coef[0] + coef[1] * h + (coef[2] * h * h if quadratic else 0.0) + coef[-1] * harmonic4


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--no-figure", action="store_true")
    ap.add_argument("--figure", default=FIGURE, help="where the figure goes (default build/figures/level_noise.png)")
    ap.add_argument("--slopes", action="store_true",
                    help="only the first-order slope K / f0 (per 1/N, N cells across the shorter axis) of each "
                         "coefficient, from the fit through all levels (docs/accuracy.md section 6.4)")
    args = ap.parse_args()
    if args.slopes:
        print("| a/b | nu | K / f0: C11, C22, C23 | per 1/(cells across a): C11, C22, C23 |")
        print("|---|---|---|---|")
        for ratio, nu in CASES:
            levels = levels_of(ratio, nu)
            ns = sorted(levels)
            k = [fit(levels, ns, c, quadratic=True) for c in ("c11", "c22", "c23")]
            across_a = max(ratio, 1.0)   # cells across a = N a/b when b is the shorter axis
            print(f"| {ratio:g} | {nu:g} | {', '.join(f'{c[1] / c[0]:+.3f}' for c in k)} | "
                  f"{', '.join(f'{c[1] / c[0] * across_a:+.3f}' for c in k)} |")
        return
    residuals = {}
    print("| a/b | nu | coefficient | levels (N) | L / f0 | rms noise, N in 56-100 / 100-200 / 200-400 / 400+ | "
          "straight line 112-296 misses f0 by |")
    print("|---|---|---|---|---|---|---|")
    for ratio, nu in CASES:
        levels = levels_of(ratio, nu)
        ns = sorted(levels)
        if not ns or ns[-1] < 400:
            print(f"| {ratio:g} | {nu:g} | (no levels beyond 400 cells across in {FILES[-1]}) |")
            continue
        for coeff in ("c11", "c22", "c23"):
            coef = fit(levels, ns, coeff, quadratic=True)
            f0 = coef[0]
            res = {n: (levels[n][coeff] - model(coef, n, levels[n]["harmonic4"], True)) / f0 for n in ns}
            residuals[(ratio, nu, coeff)] = res
            bands = []
            for lo, hi in BANDS:
                r = [res[n] for n in ns if lo <= n < hi]
                bands.append(f"{100 * math.sqrt(sum(x * x for x in r) / len(r)):.4f}" if r else "-")
            window = [n for n in ACCURATE_WINDOW if n in levels]
            miss = "-"
            if len(window) == len(ACCURATE_WINDOW):
                miss = f"{100 * (fit(levels, window, coeff, quadratic=False)[0] / f0 - 1):+.4f} %"
            print(f"| {ratio:g} | {nu:g} | {coeff.upper()} | {ns[0]}-{ns[-1]} ({len(ns)}) | {coef[2] / f0:+.2f} | "
                  f"{' / '.join(bands)} % | {miss} |")
    if args.no_figure or not residuals:
        return
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(7.5, 4.6))
    markers = "os^vDx"
    for k, (ratio, nu) in enumerate(CASES):
        res = residuals.get((ratio, nu, "c11"))
        if res is None:
            continue
        ns = sorted(res)
        ax.loglog(ns, [abs(res[n]) for n in ns], markers[k], ms=4, alpha=0.7, label=f"C11, a/b = {ratio:g}, nu = {nu:g}")
    n = np.array([56, 2048])
    ax.loglog(n, 5e-3 / n, "k--", lw=1, label="0.5 % / N")
    ax.axhline(1e-4, color="r", lw=1, label="target 1e-4")
    ax.set_xlabel("N, cells across the shorter axis")
    ax.set_ylabel("|level - smooth fit| / f0")
    ax.set_title("Staircase noise of the levels about f0 + K h + L h^2 + B harmonic4")
    ax.legend(fontsize=7, ncol=2)
    fig.tight_layout()
    path = args.figure
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    fig.savefig(path, dpi=110)
    print(f"figure: {path}")


if __name__ == "__main__":
    main()
