#!/usr/bin/env python3
"""How far a reference for a long ellipse can be trusted: its fit through
one window of fine levels against the fit through finer ones, and each
level's first-order error N (f(N) / f0 - 1) from coarse to fine.

    long_ellipse_reference.py [--ratio 10] [--nu 0.5] [--windows 296-632,448-1024,600-1024,296-1024]
                              [--ladders 56-148,72-196,96-256] [--compute] [--cache FILE[,FILE]]
                              [--out FILE] [--figure FILE]

The levels (ellipse a = sqrt(ratio), b = 1/sqrt(ratio), near-square cells,
N cells across b, normalised by the staircase area) are read from the
--cache files, as written by independent_check.py and
staircase_defect_study.py; levels beyond kcreep's 4,000,000 grid cells
come from a build with a larger max_grid_cells (docs/accuracy.md 6.7).
Each window is fitted as independent_check.py fits its reference
(f0 + K h + B harmonic4, each level referred to the ellipse; u the larger
of the 95 % interval and the change when an h^2 term is added). The last
window is the reference the levels are drawn against. --ladders fits, as
kcreep fits its finest 8 levels, the plain grids of a ladder of about 15 %
steps (56, 64, 72, 84, 96, 112, 128, 148, 172, 196, 224, 256, as far as the
cache has them) within each range, and gives its error against that
reference beside kcreep's estimate without the slope floor (t95 x SE plus a
tenth of the extrapolation from the finest level, level_fit.kcreep_estimate;
numpy). With --compute the
ladder's plain grids missing from the caches are solved (&solver method =
'iterative', tolerance = 1e-9, target_error = 0; under a minute at a/b = 10)
and appended to lab/data/long_ellipse_ladder_levels.dat. Prints markdown tables
(to --out as well); --figure draws N (f(N) / f0 - 1) of C11, C22, C23
against N (matplotlib: /usr/bin/python3 with Debian's python3-matplotlib).
Standard library otherwise; without --compute nothing is solved (seconds).
"""
import argparse
import os
import sys

sys.path[:0] = [os.path.join(os.path.dirname(os.path.abspath(__file__)), d) for d in (".", "../tools/maintenance", "../scripts/convergence", "../tests/calibration")]
import kcreep_levels as K  # noqa: E402
from independent_check import append_cache, reference  # noqa: E402

DATA = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "docs", "data")
def data_file(name):
    """The study's own data in lab/data, the refined table's levels in tools/maintenance/data."""
    own = os.path.join(os.path.dirname(os.path.abspath(__file__)), "data", name)
    if os.path.exists(own):
        return own
    tool = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tools", "maintenance", "data", name)
    return tool if os.path.exists(tool) else os.path.join(DATA, name)
LADDER_CACHE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "data", "long_ellipse_ladder_levels.dat")
COEFFS = ("c11", "c22", "c23")
#: kcreep's largest grid, mx x my (kcreep_limits max_grid_cells)
GRID_LIMIT = 4.0e6
#: kcreep's ladder from its first levels on, one level about 15 % finer at a time
LADDER = (56, 64, 72, 84, 96, 112, 128, 148, 172, 196, 224, 256)


def ladder_lines(levels, ratio, nu, ref, ranges):
    """Markdown rows: each plain ladder's fit (f0 + K h + B harmonic4) against ref."""
    from level_fit import kcreep_estimate   # numpy, only for --ladders
    slopes = K.table_slopes(ratio, nu)
    lines = ["| plain ladder (cells across b) | C11: error / estimate without the floor | C22 | C23 |",
             "|---|---|---|---|"]
    for low, high in ranges:
        ns = [n for n in LADDER if low <= n <= high and n in levels]
        if len(ns) < 5:
            continue
        referred = {n: K.refer_to_ellipse(ratio, nu, levels[n], slopes) for n in ns}
        cells = []
        for c in COEFFS:
            f0, estimate = kcreep_estimate(referred, ns, c)
            cells.append(f"{100 * (f0 / ref[c][0] - 1):+.4f} / {100 * estimate:.4f} %")
        lines.append(f"| {ns[0]}-{ns[-1]} ({len(ns)} levels) | " + " | ".join(cells) + " |")
    return lines


def draw(levels, ratio, nu, ref, window, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    slopes = K.table_slopes(ratio, nu)
    ns = sorted(levels)
    fig, axes = plt.subplots(1, 3, figsize=(13, 4), sharex=True)
    for ax, c in zip(axes, COEFFS):
        values = [n * (K.refer_to_ellipse(ratio, nu, levels[n], slopes)[c] / ref[c][0] - 1) for n in ns]
        ax.semilogx(ns, values, ".", color="C0")
        ax.axvline((GRID_LIMIT / ratio) ** 0.5, color="0.6", lw=0.8, ls="--")
        ax.set_title(f"{c.upper()}, a/b = {ratio:g}, nu = {nu:g}")
        ax.set_xlabel("N, cells across b (dashed: 4,000,000 grid cells)")
        ax.grid(alpha=0.3)
    axes[0].set_ylabel(f"N (f(N) / f0 - 1), f0 fitted through {window}")
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def main():
    if any(a in ("-h", "--help") for a in sys.argv[1:]):
        print("usage: lab/long_ellipse_reference.py\n" + __doc__)
        return
    ap = argparse.ArgumentParser(add_help=False)
    ap.add_argument("--ratio", type=float, default=10.0)
    ap.add_argument("--nu", type=float, default=0.5)
    ap.add_argument("--windows", default="296-632,448-1024,600-1024,296-1024")
    ap.add_argument("--ladders", default="")
    ap.add_argument("--cache", default=",".join(data_file(f) for f in
                                                ("fine_reference_levels_long.dat", "staircase_defect_levels.dat",
                                                 "long_ellipse_ladder_levels.dat")))
    ap.add_argument("--compute", action="store_true")
    ap.add_argument("--out", default="")
    ap.add_argument("--figure", default="")
    args = ap.parse_args()
    levels = {}
    for path in args.cache.split(","):
        levels.update(K.read_level_file(path).get((args.ratio, args.nu), {}))
    if args.compute and args.ladders:
        if not os.path.exists(LADDER_CACHE):
            with open(LADDER_CACHE, "w") as f:
                f.write("# plain ladder levels of lab/long_ellipse_reference.py --compute: ellipse c = 1, backward\n"
                        "# scheme, near-square grids (no quiet-grid choice), N cells across the shorter axis,\n"
                        "# tolerance 1e-9, coefficients normalised by the staircase area (kcreep_levels.ellipse_level)\n"
                        "# a_over_b nu N mx my n c11 c22 c23 c33 c32\n")
        for n in LADDER:
            if n not in levels:
                levels[n] = K.ellipse_level(args.ratio, args.nu, n, extra_solver=K.TARGET_ZERO + ", tolerance = 1e-9")
                append_cache(LADDER_CACHE, args.ratio, args.nu, n, levels[n])
    if not levels:
        sys.exit(f"long_ellipse_reference.py: error: no levels of a/b = {args.ratio:g}, nu = {args.nu:g} "
                 f"in {args.cache}")
    lines = ["| window (cells across b) | levels | C11: f0 (u) | C22 | C23 |", "|---|---|---|---|---|"]
    ref = last = None
    for window in args.windows.split(","):
        low, high = (int(x) for x in window.split("-"))
        chosen = {n: v for n, v in levels.items() if low <= n <= high}
        if len(chosen) < 5:
            continue
        ref, last = reference(chosen, args.ratio, args.nu), window
        lines.append(f"| {low}-{high} | {len(chosen)} | " +
                     " | ".join(f"{ref[c][0]:.5f} ({100 * ref[c][1] / ref[c][0]:.4f} %)" for c in COEFFS) + " |")
    if args.ladders and ref:
        ranges = [tuple(int(x) for x in r.split("-")) for r in args.ladders.split(",")]
        lines += ["", f"Against the fit through {last}:", ""] + ladder_lines(levels, args.ratio, args.nu, ref, ranges)
    text = "\n".join(lines) + "\n"
    print(text, end="")
    if args.out:
        with open(args.out, "w") as f:
            f.write(text)
    if args.figure and ref:
        draw(levels, args.ratio, args.nu, ref, last, args.figure)


if __name__ == "__main__":
    main()
