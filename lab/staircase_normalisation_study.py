#!/usr/bin/env python3
"""How far the ellipse levels scatter about a straight line in the cell size,
normalised three ways (docs/accuracy.md section 1, the figure
lab/figures/staircase_normalisation.png; --figure lab/figures/staircase_normalisation.png redraws it, default build/figures/).

    /usr/bin/python3 lab/staircase_normalisation_study.py [--from 32] [--to 148] [--kalker] [--levels-file F]
                                                              [--no-figure | --figure FILE]

Data: tools/maintenance/data/kalker_refined_levels.dat (the refined table's levels, stored
normalised by the staircase area; Kalker's 57 points have levels 32 to 196
cells across, --kalker keeps only those). For every ellipse in it, the
levels from --from to --to cells across are fitted
three ways, and the scatter (rms residual / C0, with the degrees of freedom
of the fit) is averaged over the ellipses:

    area      f0 + K h on the area-normalised levels (kcreep before)
    moments   f0 + K h on the levels referred to the ellipse by the
              staircase's second moments (size and aspect ratio;
              kcreep_levels.refer_to_ellipse)
    harmonic  f0 + K h + B harmonic4 on those (what kcreep fits)

The figure shows three ellipses' C11 and C23 against 1/N, the harmonic
variant with B harmonic4 taken off each level. Needs numpy and matplotlib
(Debian: python3-numpy, python3-matplotlib; /usr/bin/python3).
"""
import argparse
import os
import sys

if __name__ == "__main__" and any(a in ("-h", "--help") for a in sys.argv[1:]):
    print("usage: lab/staircase_normalisation_study.py [options]\n" + __doc__)
    sys.exit(0)
import numpy as np  # noqa: E402

sys.path[:0] = [os.path.join(os.path.dirname(os.path.abspath(__file__)), d) for d in (".", "../tools/maintenance", "../scripts/convergence", "../tests/calibration")]
import kcreep_levels as K  # noqa: E402

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
LEVELS = os.path.join(ROOT, "tools", "maintenance", "data", "kalker_refined_levels.dat")
FIGURE = os.path.join(ROOT, "build", "figures", "staircase_normalisation.png")  # --figure lab/figures/staircase_normalisation.png for the docs
SHOWN = [(1.0, 0.25), (0.7, 0.25), (2.5, 0.5)]
NAMES = ("c11", "c22", "c23")


def fit(columns, f):
    a = np.column_stack(columns)
    coef, *_ = np.linalg.lstsq(a, f, rcond=None)
    res = f - a @ coef
    return coef, np.sqrt(res @ res / (len(f) - a.shape[1])) / coef[0]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--from", dest="first", type=int, default=32)
    ap.add_argument("--to", dest="last", type=int, default=148)
    ap.add_argument("--kalker", action="store_true", help="only Kalker's 57 points")
    ap.add_argument("--levels-file", default=LEVELS)
    ap.add_argument("--no-figure", action="store_true")
    ap.add_argument("--figure", default=FIGURE, help="where the figure goes (default build/figures/staircase_normalisation.png)")
    args = ap.parse_args()
    data = K.read_level_file(args.levels_file)
    scatter = {v: [] for v in ("area", "moments", "harmonic")}
    curves = {}
    for (r, nu), levels in sorted(data.items()):
        ns = sorted(n for n in levels if args.first <= n <= args.last)
        if len(ns) < 6 or (args.kalker and 32 not in levels):
            continue
        slopes = K.table_slopes(r, nu)
        referred = [K.refer_to_ellipse(r, nu, levels[n], slopes) for n in ns]
        h = 1.0 / np.array(ns)
        h4 = np.array([x["harmonic4"] for x in referred])
        one = np.ones_like(h)
        rows = {v: [] for v in scatter}
        for c in NAMES:
            area = np.array([levels[n][c] for n in ns])
            moments = np.array([x[c] for x in referred])
            rows["area"].append(fit([one, h], area)[1])
            rows["moments"].append(fit([one, h], moments)[1])
            coef, s = fit([one, h, h4], moments)
            rows["harmonic"].append(s)
            if (r, nu) in SHOWN:
                curves[(r, nu, c)] = (ns, area, moments, moments - coef[2] * h4)
        for v in scatter:
            scatter[v].append(rows[v])
    print(f"scatter about the fit, levels {args.first} to {args.last} cells across, rms / C0 in %, "
          f"mean (worst) over {len(scatter['area'])} ellipses:")
    print("| normalisation and fit | C11 | C22 | C23 |")
    print("|---|---|---|---|")
    for v, label in (("area", "area, f0 + K h"), ("moments", "second moments, f0 + K h"),
                     ("harmonic", "second moments, f0 + K h + B harmonic4")):
        s = 100 * np.array(scatter[v])
        print(f"| {label} | " + " | ".join(f"{m:.4f} ({w:.4f})" for m, w in zip(s.mean(0), s.max(0))) + " |")
    if args.no_figure:
        return
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(2, len(SHOWN), figsize=(12, 6.5))
    for j, (r, nu) in enumerate(SHOWN):
        for i, c in enumerate(("c11", "c23")):
            ax = axes[i, j]
            ns, area, moments, harmonic = curves[(r, nu, c)]
            x = 1.0 / np.array(ns)
            for y, style, label in ((area, "o-", "area"), (moments, "s-", "second moments"),
                                    (harmonic, "^-", "second moments, harmonic taken off")):
                ax.plot(x, y, style, ms=4, label=label)
            ax.set_title(f"a/b = {r:g}, nu = {nu:g}: {c.upper()}", fontsize=10)
            ax.set_xlabel("1 / N (N cells across the shorter axis)")
            ax.grid(alpha=0.3)
            if i == 0 and j == 0:
                ax.legend(fontsize=8)
    fig.suptitle("Ellipse levels normalised three ways (tools/maintenance/data/kalker_refined_levels.dat)")
    fig.tight_layout()
    path = args.figure
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    fig.savefig(path, dpi=110)
    print(f"figure: {path}")


if __name__ == "__main__":
    main()
