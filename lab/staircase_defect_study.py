#!/usr/bin/env python3
"""Where the staircase noise of ellipses long in x comes from, and whether
fitting it away lets the accurate mode stop sooner (docs/accuracy.md 6.3,
the figure lab/figures/staircase_defects.png; --figure lab/figures/staircase_defects.png redraws it, default build/figures/).

    /usr/bin/python3 lab/staircase_defect_study.py [--compute] [--no-figure | --figure FILE]

Each level (N cells across the shorter axis, near-square cells; data in
lab/data/staircase_defect_levels.dat, a/b = 5 from 296 also from
tools/maintenance/data/fine_reference_levels_long.dat) is referred to the ellipse by its
staircase's second moments (kcreep_levels.refer_to_ellipse), as kcreep's
levels are. Its staircase is then described by the defects of its ends:
    row j:    d_j = (cells in row j) dx / (2a) - s_j,     s_j = sqrt(1 - Y_j^2)
    column i: e_i = (cells in column i) dy / (2b) - t_i,  t_i = sqrt(1 - X_i^2)
and weighted sums R_p = sum s_j^p d_j dy/b, Q_p = sum t_i^p e_i dx/a
(p = -1 ... 3; R_0 and Q_0 are the area defect, which the normalisation
already takes out). Printed:
  1. the rms scatter of levels 56-120 about f0 + K h + L h^2 + B harmonic4,
     with the boundary defect's harmonics cos(2k theta), k = 3-8, added, and
     with each pair (R_p, Q_q) added: the best pair and the pair R_1, Q_-1/2;
  2. at a/b = 10, the pair's coefficients fitted on levels 40-79 and applied
     unchanged to levels 80-120 (does the pair describe the noise, or fit it?);
  3. kcreep's estimator (the straight line f0 + K h + B harmonic4 through the
     finest 8 of its levels 56, 64, ..., t95 x SE + 0.1 |f0 - f(finest)|)
     and the same with the combination R_1 - 0.43 Q_-1/2 as a fourth column,
     each against a reference fitted through levels 296-512 (a/b = 10) or
     296-576 (a/b = 5).
--compute first runs build/kcreep for levels missing from the data file
(about 6 minutes). Needs numpy (and matplotlib for the figure):
/usr/bin/python3 with Debian's python3-numpy, python3-matplotlib.
"""
import argparse
import itertools
import math
import os
import sys

if __name__ == "__main__" and any(a in ("-h", "--help") for a in sys.argv[1:]):
    print(__doc__)
    sys.exit(0)
import numpy as np  # noqa: E402

sys.path[:0] = [os.path.join(os.path.dirname(os.path.abspath(__file__)), d) for d in (".", "../tools/maintenance", "../scripts/convergence", "../tests/calibration")]
import kcreep_levels as K  # noqa: E402
from level_fit import fit_levels, kcreep_estimate  # noqa: E402

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
DATA = os.path.join(ROOT, "lab", "data", "staircase_defect_levels.dat")
LONG = os.path.join(ROOT, "tools", "maintenance", "data", "fine_reference_levels_long.dat")
FIGURE = os.path.join(ROOT, "build", "figures", "staircase_defects.png")  # --figure lab/figures/staircase_defects.png for the docs
NU = 0.25
RATIOS = (0.5, 1.0, 2.0, 5.0, 10.0)
DENSE = list(range(40, 121))
LADDER = [56, 64, 72, 84, 96, 112, 128, 148, 172, 196, 224, 256]
REFERENCE = {5.0: [296, 340, 384, 448, 512, 576], 10.0: [296, 340, 384, 448, 512]}
POWERS = (-1, -0.5, 0, 0.5, 1, 2, 3)
HARMONICS = range(3, 9)     # cos(2k theta) beyond the second moments (k = 1) and harmonic4 (about k = 2)
PAIR = ("R1", "Q-0.5")
COMBINATION = -0.43        # Q's weight in the one-column combination (the pair's ratio at a/b = 10, section 1)
COEFFS = ("c11", "c22", "c23")


def compute_missing():
    """Run kcreep for the levels the data file lacks and append them."""
    have = K.read_level_file(DATA)
    wanted = {r: list(DENSE) for r in RATIOS}
    for r in REFERENCE:
        wanted[r] += [n for n in LADDER if n > 120] + (REFERENCE[r] if r == 10.0 else [])
    with open(DATA, "a") as out:
        for r, levels in wanted.items():
            for n in levels:
                if n in have.get((r, NU), {}):
                    continue
                lv = K.ellipse_level(r, NU, n, extra_solver=", target_error = 0, tolerance = 1e-9")
                out.write(f"{r:g} {NU:g} {n} {lv['mx']} {lv['my']} {lv['n']} "
                          + " ".join(f"{lv[k]:.13e}" for k in K.COEFFS) + f" {lv['time']:.3f}\n")
                out.flush()


def end_defects(ratio, mx, my):
    """{name: weighted defect sum} of the staircase on an mx x my grid (the names R_p, Q_p)."""
    a, b = math.sqrt(ratio), 1 / math.sqrt(ratio)
    dx, dy = 2 * a / mx, 2 * b / my
    x = (-a + dx * (np.arange(mx) + 0.5)) / a
    y = (-b + dy * (np.arange(my) + 0.5)) / b
    inside = x[None, :] ** 2 + y[:, None] ** 2 <= 1
    s, t = np.sqrt(1 - y ** 2), np.sqrt(1 - x ** 2)
    d = inside.sum(axis=1) * dx / (2 * a) - s
    e = inside.sum(axis=0) * dy / (2 * b) - t
    out = {f"R{p:g}": np.sum(s ** p * d) * dy / b for p in POWERS}
    out.update({f"Q{p:g}": np.sum(t ** p * e) * dx / a for p in POWERS})
    # the boundary defect's harmonics: sum over the cells of cos(2k theta) (zero over the ellipse itself)
    theta = np.arctan2(np.broadcast_to(y[:, None], inside.shape), np.broadcast_to(x[None, :], inside.shape))
    out.update({f"H{k}": np.sum(np.cos(2 * k * theta)[inside]) * (dx / a) * (dy / b) for k in HARMONICS})
    return out


def load(ratio):
    """Levels N -> {c11, c22, c23 referred to the ellipse, harmonic4, the defect sums}."""
    merged = dict(K.read_level_file(DATA).get((ratio, NU), {}))
    if ratio == 5.0:
        merged.update(K.read_level_file(LONG).get((ratio, NU), {}))
    slopes = K.table_slopes(ratio, NU)
    levels = {}
    for n in sorted(merged):
        levels[n] = K.refer_to_ellipse(ratio, NU, merged[n], slopes)
        levels[n].update(end_defects(ratio, merged[n]["mx"], merged[n]["my"]))
    return levels


def column(name):
    return lambda level: level[name]


def combination(level):
    return level[PAIR[0]] + COMBINATION * level[PAIR[1]]


def scatter_table(data):
    print("1. rms scatter of levels 56-120 (relative, %) about f0 + K h + L h^2 + B harmonic4, nu = 0.25")
    names = [f"R{p:g}" for p in POWERS] + [f"Q{p:g}" for p in POWERS]
    print("| a/b | coefficient | harmonic4 only | + cos(2k theta), k = 3-8 | + R_1, Q_-1/2 (Q/R ratio) | best pair "
          "| its scatter |")
    print("|---|---|---|---|---|---|---|")
    for ratio in RATIOS:
        levels = data[ratio]
        ns = [n for n in levels if 56 <= n <= 120]
        for name in COEFFS:
            c, _, _, res = fit_levels(levels, ns, name, quadratic=True)
            base = np.sqrt(np.mean(res ** 2)) / c[0]
            c2, _, _, res2 = fit_levels(levels, ns, name, quadratic=True, extra=[column(p) for p in PAIR])
            pair = np.sqrt(np.mean(res2 ** 2)) / c2[0]
            c3, _, _, res3 = fit_levels(levels, ns, name, quadratic=True, extra=[column(f"H{m}") for m in HARMONICS])
            harmonics = np.sqrt(np.mean(res3 ** 2)) / c3[0]
            best = min((np.sqrt(np.mean(fitted[3] ** 2)), p, q)
                       for p, q in itertools.combinations(names, 2)
                       for fitted in [fit_levels(levels, ns, name, quadratic=True, extra=[column(p), column(q)])]
                       if fitted[1] == fitted[1])
            print(f"| {ratio:g} | {name.upper()} | {100 * base:.4f} | {100 * harmonics:.4f} "
                  f"| {100 * pair:.4f} ({c2[5] / c2[4]:.2f}) "
                  f"| {best[1]}, {best[2]} | {100 * best[0] / c[0]:.4f} |")


def out_of_sample(data):
    print("\n2. a/b = 10: the pair fitted on levels 40-79, applied unchanged to levels 80-120 (rms, %)")
    levels = data[10.0]
    coarse = [n for n in levels if 40 <= n < 80]
    fine = [n for n in levels if 80 <= n <= 120]
    print("| coefficient | fine levels as they are | less the coarse levels' pair | pair coefficients / f0, coarse; fine |")
    print("|---|---|---|---|")
    for name in COEFFS:
        c = fit_levels(levels, coarse, name, quadratic=True, extra=[column(p) for p in PAIR])[0]
        cf = fit_levels(levels, fine, name, quadratic=True, extra=[column(p) for p in PAIR])[0]
        c0, _, _, res0 = fit_levels(levels, fine, name, quadratic=True)
        corrected = {n: dict(levels[n], **{name: levels[n][name] - c[4] * levels[n][PAIR[0]] - c[5] * levels[n][PAIR[1]]})
                     for n in fine}
        c1, _, _, res1 = fit_levels(corrected, fine, name, quadratic=True)
        print(f"| {name.upper()} | {100 * np.sqrt(np.mean(res0 ** 2)) / c0[0]:.4f} "
              f"| {100 * np.sqrt(np.mean(res1 ** 2)) / c1[0]:.4f} "
              f"| {c[4] / c[0]:.2f}, {c[5] / c[0]:.2f}; {cf[4] / cf[0]:.2f}, {cf[5] / cf[0]:.2f} |")


def estimates(levels, ratio, coeff):
    """[(finest N, kcreep's estimate, its error, with the combination: estimate, error)] against the reference."""
    ref = fit_levels(levels, REFERENCE[ratio], coeff)[0][0]
    rows = []
    for end in range(8, len(LADDER) + 1):
        ns = LADDER[:end]
        f0, old = kcreep_estimate(levels, ns, coeff)
        f0_with, new = kcreep_estimate(levels, ns, coeff, extra=[combination])
        rows.append((ns[-1], old, abs(f0 / ref - 1), new, abs(f0_with / ref - 1)))
    return ref, rows


def estimate_table(data):
    print("\n3. kcreep's estimator and the one with R_1 - 0.43 Q_-1/2 added, against references (%)")
    print("| a/b | coefficient | finest level | kcreep's: estimate | error | with the combination: estimate | error |")
    print("|---|---|---|---|---|---|---|")
    for ratio in (5.0, 10.0):
        for name in COEFFS:
            ref, rows = estimates(data[ratio], ratio, name)
            moved = fit_levels(data[ratio], REFERENCE[ratio], name, extra=[combination])[0][0] / ref - 1
            print(f"| {ratio:g} | {name.upper()} | reference {ref:.6f} (with the column in its own fit: "
                  f"{100 * moved:+.5f} %) | | | | |")
            for n, old, err_old, new, err_new in rows:
                if n < 148:
                    continue
                print(f"| {ratio:g} | {name.upper()} | {n} | {100 * old:.4f} | {100 * err_old:.4f} "
                      f"| {100 * new:.4f} | {100 * err_new:.4f} |")


def figure(data, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4.2))
    levels = data[10.0]
    ns = [n for n in levels if 56 <= n <= 120]
    c, _, _, res = fit_levels(levels, ns, "c22", quadratic=True)
    c2, _, _, res2 = fit_levels(levels, ns, "c22", quadratic=True, extra=[column(p) for p in PAIR])
    left.plot(ns, 100 * res / c[0], "o-", ms=3, label="f0 + K h + L h² + B harmonic4")
    left.plot(ns, 100 * res2 / c2[0], "s-", ms=3, label="... + row and column end defects (R₁, Q₋½)")
    left.set_xlabel("cells across b (a/b = 10, 10 N x N cells)")
    left.set_ylabel("C22: level minus fit (%)")
    left.set_title("The levels' scatter, a/b = 10, nu = 0.25")
    left.legend(fontsize=8)
    for ratio, style in ((5.0, "o"), (10.0, "s")):
        _, rows = estimates(data[ratio], ratio, "c22")
        n = [r[0] for r in rows]
        right.semilogy(n, [100 * r[1] for r in rows], style + "-", color="C0", ms=4,
                       label=f"kcreep's estimate, a/b = {ratio:g}")
        right.semilogy(n, [100 * r[2] for r in rows], style + ":", color="C0", ms=4, label=f"its error, a/b = {ratio:g}")
        right.semilogy(n, [100 * r[3] for r in rows], style + "-", color="C3", ms=4,
                       label=f"with the end defects: estimate, a/b = {ratio:g}")
        right.semilogy(n, [100 * r[4] for r in rows], style + ":", color="C3", ms=4, label=f"its error, a/b = {ratio:g}")
    right.axhline(0.01, color="k", lw=0.8)
    right.set_xlabel("finest level (cells across b)")
    right.set_ylabel("C22, relative (%)")
    right.set_title("Estimate and error against references")
    right.legend(fontsize=7)
    fig.tight_layout()
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    fig.savefig(path, dpi=110)
    print(f"\nfigure: {path}")


def main():
    parser = argparse.ArgumentParser(description="staircase end defects of ellipses long in x")
    parser.add_argument("--compute", action="store_true", help="run kcreep for missing levels first")
    parser.add_argument("--no-figure", action="store_true")
    parser.add_argument("--figure", default=FIGURE, help="where the figure goes (default build/figures/staircase_defects.png)")
    args = parser.parse_args()
    if args.compute:
        compute_missing()
    data = {r: load(r) for r in RATIOS}
    scatter_table(data)
    out_of_sample(data)
    estimate_table(data)
    if not args.no_figure:
        figure(data, args.figure)


if __name__ == "__main__":
    main()
