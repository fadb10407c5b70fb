#!/usr/bin/env python3
"""The accurate mode on a long ellipse stopped at each of its levels, against
a reference from much finer grids: does the estimate still bound the error
as the levels go finer?

    long_ellipse_stops.py [--ratio 10] [--nu 0,0.25,0.5] [--stops 96,112,...,224]
                          [--target 1e-4] [--cache FILE[,FILE]] [--levels 296,...,512]
                          [--compute] [--out FILE] [--figure FILE]

For each nu and each stop W (cells across the shorter axis of a level of
kcreep's ladder) kcreep runs the ellipse a = sqrt(ratio), b = 1/sqrt(ratio)
with &solver target_error = --target and cell_budget = the patch cells kcreep
counts for the wanted grid of W (ellipse_fill x mx x my, as
kcreep_error_run.run_ellipse_levels): the run solves its ladder up to W and
stops there, or earlier when it is `ok`. Its C11, C22, C23 and their estimates are compared
with the reference of lab/independent_check.py (levels --levels from the
--cache files, fitted by f0 + K h + B harmonic4; u the larger of the fit's
95 % interval and the change when an h^2 term is added). With --compute the
reference levels missing from every cache file are computed (near-square
grids, &solver method = 'iterative', tolerance = 1e-9, target_error = 0, as
independent_check.py --tolerance 1e-9) and appended to the first file; a
level of 768 cells across at a/b = 10 takes about 9 GB and a few minutes.

Prints a table (markdown with --out) and draws, with --figure, each
coefficient's error with the stated estimate as its bar, per stop and nu.
Needs matplotlib only for --figure (/usr/bin/python3 with Debian's
python3-matplotlib).
"""
import argparse
import math
import os
import sys

sys.path[:0] = [os.path.join(os.path.dirname(os.path.abspath(__file__)), d) for d in (".", "../tools/maintenance", "../scripts/convergence", "../tests/calibration")]
import kcreep_levels as K  # noqa: E402
from independent_check import append_cache, reference  # noqa: E402

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
DATA = os.path.join(ROOT, "docs", "data")
def data_file(name):
    """The study's own data in lab/data, the refined table's levels in tools/maintenance/data."""
    own = os.path.join(os.path.dirname(os.path.abspath(__file__)), "data", name)
    if os.path.exists(own):
        return own
    tool = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tools", "maintenance", "data", name)
    return tool if os.path.exists(tool) else os.path.join(DATA, name)
#: kcreep_error_run ellipse_fill: the share of the bounding grid kcreep counts as patch cells
ELLIPSE_FILL = 0.79
COEFFS = (("c11", "err11"), ("c22", "err22"), ("c23", "err23"))


def stop_budget(ratio, cells):
    """The cell budget that lets kcreep's ladder reach `cells` across and no further."""
    mx, my = K.square_grid(ratio, cells)
    return ELLIPSE_FILL * mx * my


def main():
    ap = argparse.ArgumentParser(add_help=False)
    ap.add_argument("--ratio", type=float, default=10.0)
    ap.add_argument("--nu", default="0,0.25,0.5")
    ap.add_argument("--stops", default="96,112,128,148,172,196,224")
    ap.add_argument("--target", type=float, default=1e-4)
    ap.add_argument("--cache", default=",".join(data_file(f) for f in
                                                ("fine_reference_levels_long.dat", "staircase_defect_levels.dat")))
    ap.add_argument("--levels", default="296,340,384,448,512")
    ap.add_argument("--compute", action="store_true")
    ap.add_argument("--out", default="")
    ap.add_argument("--figure", default="")
    args = ap.parse_args()
    ratio = args.ratio
    nus = [float(x) for x in args.nu.split(",")]
    stops = [int(x) for x in args.stops.split(",")]
    levels = [int(x) for x in args.levels.split(",")]
    cached = {}
    for path in args.cache.split(","):
        for key, value in K.read_level_file(path).items():
            cached.setdefault(key, {}).update(value)

    a, b = math.sqrt(ratio), 1 / math.sqrt(ratio)
    lines = [f"| nu | stop (wanted) | grid used | wall | verdict | C11: error / estimate | C22 | C23 |",
             "|---|---|---|---|---|---|---|---|"]
    points = []    # (nu, my, coefficient, error, estimate, u)
    bounded = total = 0
    if args.compute:
        first = args.cache.split(",")[0]
        for nu in nus:
            have = cached.setdefault((ratio, nu), {})
            for n in levels:
                if n not in have:
                    have[n] = K.ellipse_level(ratio, nu, n, extra_solver=K.TARGET_ZERO + ", tolerance = 1e-9")
                    append_cache(first, ratio, nu, n, have[n])
                    print(f"reference level a/b = {ratio:g}, nu = {nu:g}, {n} across: {have[n]['time']:.0f} s",
                          flush=True)
    for nu in nus:
        have = {n: v for n, v in cached.get((ratio, nu), {}).items() if n in levels}
        if len(have) < 4:
            sys.exit(f"long_ellipse_stops.py: the cache has {len(have)} of the reference levels {args.levels} for "
                     f"a/b = {ratio:g}, nu = {nu:g} (compute them with lab/independent_check.py --cache ...)")
        ref = reference(have, ratio, nu)
        for stop in stops:
            nml = (f"&patch shape = 'ellipse', semi_a = {a!r}, semi_b = {b!r} /\n&material nu = {nu!r} /\n"
                   f"&solver target_error = {args.target!r}, cell_budget = {stop_budget(ratio, stop)!r} /\n"
                   f"&output table_file = 'case.tab' /\n")
            rows, wall, _ = K.run_kcreep(nml)
            row = rows[-1]
            cells = []
            for c, e in COEFFS:
                f0, u = ref[c]
                err = float(row[c]) / f0 - 1
                stated = float(row[e])
                total += 1
                bounded += stated >= abs(err)
                points.append((nu, int(row["my"]), c, err, stated, u / abs(f0)))
                cells.append(f"{100 * err:+.4f} / {100 * stated:.4f} %" + ("" if stated >= abs(err) else " (not bounded)"))
            lines.append(f"| {nu:g} | {stop} | {row['mx']} x {row['my']} | {wall:.1f} s | {row['verdict']} | " +
                         " | ".join(cells) + " |")
            print(lines[-1], flush=True)
        lines.append("| | reference (u) | | | | " + " | ".join(
            f"{ref[c][0]:.5f} ({100 * ref[c][1] / abs(ref[c][0]):.4f} %)" for c, _ in COEFFS) + " |")
        print(lines[-1], flush=True)
    lines += ["", f"a/b = {ratio:g}, target_error = {args.target:g}: the estimate bounded the error in {bounded} of "
              f"{total} coefficients; reference levels {args.levels} cells across (errors signed: kcreep - reference)."]
    print(lines[-1])
    if args.out:
        with open(args.out, "w") as f:
            f.write("\n".join(lines) + "\n")
    if args.figure:
        draw(points, nus, ratio, args.target, args.figure)


def draw(points, nus, ratio, target, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 3, figsize=(13, 4.2), sharex=True)
    for ax, (c, _) in zip(axes, COEFFS):
        for k, nu in enumerate(nus):
            sel = [p for p in points if p[0] == nu and p[2] == c]
            x = [p[1] * (1 + 0.012 * (k - 1)) for p in sel]
            ax.errorbar(x, [100 * p[3] for p in sel], yerr=[100 * p[4] for p in sel], fmt="o", capsize=3,
                        label=f"nu = {nu:g}: error, bar = kcreep's estimate")
            u = sel[0][5] if sel else 0
            ax.axhspan(-100 * u, 100 * u, color=f"C{k}", alpha=0.08)
        limit = 100 * target * (3 if c == "c23" else 1)
        ax.axhline(0, color="k", lw=0.8)
        for s in (-1, 1):
            ax.axhline(s * limit, color="grey", ls=":", lw=0.8)
        ax.set_title(f"{c.upper()}, a/b = {ratio:g} (dotted: the target; bands: the reference's u)", fontsize=9)
        ax.set_xlabel("cells across b of the finest level")
        ax.set_ylabel("error against the reference [%]")
    axes[0].legend(fontsize=7, loc="lower right")
    fig.tight_layout()
    fig.savefig(path, dpi=110)


if __name__ == "__main__":
    if any(a in ("-h", "--help") for a in sys.argv[1:]):
        print("usage: lab/long_ellipse_stops.py [options]\n" + __doc__)
        sys.exit(0)
    main()
