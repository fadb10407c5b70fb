#!/usr/bin/env python3
"""Kalker's table E3 recomputed by kcreep, with error bars.

    refine_kalker_table.py [--levels 56,64,72,84,96,112,128,148] [--fit-from 56] [--ratios 0.5,1,2]
                           [--nu 0,0.25,0.5] [--max-seconds S] [--table-only]
                           [--fine-levels FILE[,FILE]] [--fine-from 296] [--out FILE]
                           [--fine-check N]

For every a/b and nu of data/kalker-table-E3.dat: the ellipse with c = 1 on
near-square grids with N cells across its shorter axis (the levels), the
backward scheme on the iterative path, coefficients normalised by the area
of the cells inside the ellipse (as stored; each level is then referred to
the ellipse by the staircase's second moments, kcreep_levels.refer_to_ellipse,
as kcreep's own ellipse levels are). Each level's numbers are appended to
tools/maintenance/data/kalker_refined_levels.dat as soon as they exist, so the script
resumes where it stopped (run it in chunks). The table
docs/data/kalker_refined.dat is then rebuilt from all levels present:

    value  the least-squares fit f0 + K h + B harmonic4 through the levels
           (order fixed at 1; harmonic4 the staircase's four-fold harmonic)
    u      max(t95 * standard error of f0, |f0 - f0'|) + 0.1 |f0 - f(finest)|,
           f0' the fit of f0 + K h + L h^2 + B harmonic4: the scatter of the
           levels (the staircase noise) or the model error, whichever is larger,
           plus the order's uncertainty (kcreep_refine_estimate order_margin); absolute units

The fit uses the levels from --fit-from cells across up (the coarser ones
carry more staircase noise). Cases with fewer than 5 such levels are left
out of the table.

Fine rows: where the --fine-levels files (default: the references of
docs/accuracy.md, "The refined table of ellipses", fine_reference_levels.dat and
fine_reference_levels_long.dat; near-square cells, as written by
independent_check.py) hold at least 6 levels from --fine-from cells across
up for a point of the table, its row is fitted through those levels alone,
the same way (Nmin Nmax levels say which). Their u is a tenth to a third of
the coarse rows', small enough for target_error = 1e-4 (docs/accuracy.md, "The refined table of ellipses"). Levels beyond kcreep's 4,000,000 grid cells in those files came from a
build with a larger limit (docs/accuracy.md, "The refined table of ellipses").

Each level is referred to the ellipse with slopes d ln C / d ln(a/b) taken
from the table itself, so the table is rebuilt until it no longer changes
(two or three rounds): it is the fixed point of its levels, and the test
refined_table_module rebuilds it (--table-only --out) and compares.

--fine-check N (nothing solved, nothing written): for every fine row, the
coarse row (the table's own levels) against it, and where the row has levels
beyond N cells across, the row fitted through its levels up to N against
the row through all of them; markdown on standard output (docs/accuracy.md, "The refined table of ellipses").
"""
import argparse
import math
import os
import shutil
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import kcreep_levels as K  # noqa: E402

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
LEVELS_FILE = os.path.join(ROOT, "tools", "maintenance", "data", "kalker_refined_levels.dat")
TABLE_FILE = os.path.join(ROOT, "docs", "data", "kalker_refined.dat")
KALKER_FILE = os.path.join(ROOT, "data", "kalker-table-E3.dat")
FINE_LEVELS = ",".join(os.path.join(ROOT, "tools", "maintenance", "data", name)
                       for name in ("fine_reference_levels.dat", "fine_reference_levels_long.dat"))
#: the fewest fine levels a fine row is fitted through
FINE_MIN_LEVELS = 6

LEVEL_COLUMNS = ["a_over_b", "nu", "N", "mx", "my", "n", "c11", "c22", "c23", "c33", "c32", "iterations", "seconds"]


def kalker_points():
    """[(a_over_b, nu, {c11, c22, c23})] of Kalker's table, in table order."""
    out = []
    with open(KALKER_FILE) as f:
        for line in f:
            if line.startswith("#") or not line.strip():
                continue
            p = line.split()
            g = float(p[1])
            r = g if p[0] == "a/b" else 1 / g
            v = [float(x) for x in p[2:11]]
            for j, nu in enumerate((0.0, 0.25, 0.5)):
                out.append((r, nu, {"c11": v[j], "c22": v[3 + j], "c23": v[6 + j]}))
    return out


#: the table's columns of nu: Kalker's three and the two between them
TABLE_NU = (0.0, 0.125, 0.25, 0.375, 0.5)


def table_points():
    """[(a_over_b, nu)] of the refined table: Kalker's rows (g = b/a or a/b =
    0.1 ... 1), the rows halfway between them in g (0.15, 0.25, ... 0.95 on
    each side) and g = 0.125 (the end interval is the widest in ln g), at the
    nu of TABLE_NU; increasing a/b."""
    gs = [round(0.1 * k, 2) for k in range(1, 11)] + [round(0.05 + 0.1 * k, 2) for k in range(1, 10)] + [0.125]
    ratios = sorted(set(gs) | {1 / g for g in gs if g < 1})
    return [(r, nu) for r in ratios for nu in TABLE_NU]


def key(r, nu):
    """As the levels file writes them (6 significant digits)."""
    return (f"{r:.6g}", f"{nu:.6g}")


def read_levels():
    """{key(a/b, nu): {N: level}} of the levels file."""
    return {key(r, nu): levels for (r, nu), levels in K.read_level_file(LEVELS_FILE).items()}


def append_level(r, nu, N, d):
    new = not os.path.exists(LEVELS_FILE)
    with open(LEVELS_FILE, "a") as f:
        if new:
            f.write("# kcreep levels for the refined Kalker table (tools/maintenance/refine_kalker_table.py): ellipse c = 1,\n"
                    "# backward scheme, N cells across the shorter axis, coefficients normalised by the staircase area\n")
            f.write("# " + " ".join(LEVEL_COLUMNS) + "\n")
        f.write(f"{r:.6g} {nu:.6g} {N} {d['mx']} {d['my']} {d['n']} {d['c11']:.12e} {d['c22']:.12e} "
                f"{d['c23']:.12e} {d['c33']:.12e} {d['c32']:.12e} {d['iterations']} {d['time']:.3f}\n")


def lstsq_columns(columns, fs):
    """f0 and its standard error of the least-squares fit of fs by the columns
    (lists, the first all ones); NaN error without degrees of freedom."""
    m, k = len(fs), len(columns)
    scale = [max(abs(v) for v in col) or 1.0 for col in columns]
    A = [[columns[a][i] / scale[a] for a in range(k)] for i in range(m)]
    ATA = [[sum(A[i][a] * A[i][b] for i in range(m)) for b in range(k)] for a in range(k)]
    ATf = [sum(A[i][a] * fs[i] for i in range(m)) for a in range(k)]
    c = K.solve(ATA, ATf)
    res = [fs[i] - sum(A[i][a] * c[a] for a in range(k)) for i in range(m)]
    dof = m - k
    if dof <= 0:
        return c[0] / scale[0], float("nan"), dof
    s2 = sum(x * x for x in res) / dof
    e0 = K.solve(ATA, [1.0] + [0.0] * (k - 1))[0]     # (ATA^-1)_00
    return c[0] / scale[0], math.sqrt(s2 * e0) / scale[0], dof


#: the share of the extrapolation f0 - f(finest) counted as the order's
#: uncertainty (as kcreep_refine_estimate order_margin)
ORDER_MARGIN = 0.1


def refined_value(levels, coeff):
    """(value, u) from {N: level referred to the ellipse (K.refer_to_ellipse)}:
    the fit f0 + K h + B harmonic4 (as kcreep's own ellipse levels), u the
    larger of its 95 % interval and its change when an h^2 term is added,
    plus ORDER_MARGIN times the extrapolation from the finest level."""
    Ns = sorted(levels)
    hs = [1.0 / N for N in Ns]
    h4 = [levels[N]["harmonic4"] for N in Ns]
    fs = [levels[N][coeff] for N in Ns]
    ones = [1.0] * len(Ns)
    f1, se1, dof1 = lstsq_columns([ones, hs, h4], fs)
    f2, _, _ = lstsq_columns([ones, hs, [h * h for h in hs], h4], fs)
    u = max(K.student_t95(dof1) * se1, abs(f1 - f2)) + ORDER_MARGIN * abs(f1 - fs[-1])
    return f1, u


def read_fine_levels(paths):
    """{key(a/b, nu): {N: level}} of the fine levels files (later files add to earlier ones).
    A file named but missing is an error: without it the table would lose its fine rows."""
    fine = {}
    for path in paths:
        if not os.path.isfile(path):
            sys.exit(f"refine_kalker_table.py: --fine-levels: {path}: no such file (give existing levels files, "
                     "or '' for none)")
        for (r, nu), levels in K.read_level_file(path).items():
            fine.setdefault(key(r, nu), {}).update(levels)
    return fine


def row_levels(data, fine, r, nu, fit_from, fine_from):
    """The levels a row is fitted through: the fine ones where there are
    enough of them, else the table's own from fit_from cells across."""
    lv = {N: v for N, v in fine.get(key(r, nu), {}).items() if N >= fine_from}
    if len(lv) >= FINE_MIN_LEVELS:
        return lv
    return {N: v for N, v in data.get(key(r, nu), {}).items() if N >= fit_from}


def write_table(data, points, fit_from, fine=None, fine_from=296, out=TABLE_FILE):
    """Rebuild the table `out` from the levels; the slopes of each level's
    reference to the ellipse come from `out` as it was."""
    rows = []
    for r, nu in points:
        lv = row_levels(data, fine or {}, r, nu, fit_from, fine_from)
        if len(lv) < 5:
            continue
        slopes = K.table_slopes(r, nu, out)
        lv = {N: K.refer_to_ellipse(r, nu, v, slopes) for N, v in lv.items()}
        vals = []
        for c in ("c11", "c22", "c23", "c33", "c32"):
            vals.extend(refined_value(lv, c))
        rows.append((r, nu, min(lv), max(lv), len(lv), vals))
    tmp = out + ".tmp"
    with open(tmp, "w") as f:
        f.write("# Kalker's creep coefficients recomputed by kcreep (tools/maintenance/refine_kalker_table.py):\n"
                "# ellipse with c = sqrt(ab) = 1, backward scheme on near-square cells, levels from Nmin to Nmax\n"
                f"# cells across the shorter axis (rows with Nmin >= {fine_from}: the fine rows of docs/accuracy.md, \"The refined table of ellipses\",\n"
                "# from the reference levels of 6.1 and 6.7), each referred to the ellipse by the staircase's second moments\n"
                "# (tools/maintenance/kcreep_levels.py refer_to_ellipse), least-squares fit f0 + K h + B harmonic4;\n"
                "# u = absolute uncertainty: max(95 % interval of the fit, change when an h^2 term is added)\n"
                "# + 0.1 x the extrapolation from the finest level (the order is 1 to within 0.06).\n"
                "# c32 = f32/(G c^3) (= -c23 by reciprocity, kept as a check), c33 = f33/(G c^4).\n")
        f.write("# a_over_b nu c11 u11 c22 u22 c23 u23 c33 u33 c32 u32 Nmin Nmax levels\n")
        for r, nu, nmin, nmax, nl, v in rows:
            f.write(f"{r:.6g} {nu:.6g} " + " ".join(f"{x:.6g}" for x in v) + f" {nmin} {nmax} {nl}\n")
    os.replace(tmp, out)
    return rows


def fine_check(data, fine, points, fit_from, fine_from, upto):
    """Markdown: each fine row against its coarse row, and its levels up to
    `upto` against all of them; counts of differences within the stated u."""
    coeffs = ("c11", "c22", "c23")
    coarse_lines, trunc_lines = [], []
    coarse_in = trunc_in = coarse_n = trunc_n = 0
    for r, nu in points:
        fine_lv = row_levels(data, fine, r, nu, fit_from, fine_from)
        if min(fine_lv, default=0) < fine_from:
            continue                                   # not a fine row
        slopes = K.table_slopes(r, nu)
        refer = {N: K.refer_to_ellipse(r, nu, v, slopes) for N, v in fine_lv.items()}
        best = {c: refined_value(refer, c) for c in coeffs}
        coarse = {N: K.refer_to_ellipse(r, nu, v, slopes) for N, v in data.get(key(r, nu), {}).items() if N >= fit_from}
        cells = []
        for c in coeffs:
            v, u = refined_value(coarse, c)
            diff = v / best[c][0] - 1
            coarse_in += abs(v - best[c][0]) <= u
            coarse_n += 1
            cells.append(f"{100 * diff:+.4f} / {100 * u / v:.4f} %")
        coarse_lines.append(f"| {r:.6g} | {nu:g} | {min(coarse)}-{max(coarse)} | {max(refer)} | " + " | ".join(cells) + " |")
        early = {N: v for N, v in refer.items() if N <= upto}
        if len(early) < FINE_MIN_LEVELS or len(early) == len(refer):
            continue
        cells = []
        for c in coeffs:
            v, u = refined_value(early, c)
            trunc_in += abs(v - best[c][0]) <= u
            trunc_n += 1
            cells.append(f"{100 * (v / best[c][0] - 1):+.4f} / {100 * u / v:.4f} / {100 * best[c][1] / best[c][0]:.4f} %")
        trunc_lines.append(f"| {r:.6g} | {nu:g} | {min(early)}-{max(early)} | {min(refer)}-{max(refer)} | "
                           + " | ".join(cells) + " |")
    print("| a/b | nu | coarse levels | fine to | C11: coarse - fine / coarse u | C22 | C23 |")
    print("|---|---|---|---|---|---|---|")
    print("\n".join(coarse_lines))
    print(f"\nThe coarse row's u bounded its difference from the fine row in {coarse_in} of {coarse_n}.\n")
    print(f"| a/b | nu | levels | against | C11: difference / u of the shorter fit / u of the longer | C22 | C23 |")
    print("|---|---|---|---|---|---|---|")
    print("\n".join(trunc_lines))
    print(f"\nThe fit through levels up to {upto} bounded its difference from the fit through all in "
          f"{trunc_in} of {trunc_n}.")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--levels", default="56,64,72,84,96,112,128,148")
    ap.add_argument("--fit-from", type=int, default=56, help="fit the levels from this many cells across up")
    ap.add_argument("--ratios", default="", help="comma-separated a/b subset (default: all rows of the table)")
    ap.add_argument("--nu", default=",".join(f"{nu:g}" for nu in TABLE_NU))
    ap.add_argument("--max-seconds", type=float, default=float("inf"), help="stop starting new levels after this")
    ap.add_argument("--table-only", action="store_true")
    ap.add_argument("--fine-levels", default=FINE_LEVELS,
                    help="comma-separated levels files of fine rows ('' for none)")
    ap.add_argument("--fine-from", type=int, default=296, help="a fine row's levels from this many cells across up")
    ap.add_argument("--out", default=TABLE_FILE, help="the table to write (its slopes start from the committed table's)")
    ap.add_argument("--fine-check", type=int, default=0, metavar="N",
                    help="compare the fine rows with the coarse ones and with their own levels up to N")
    args = ap.parse_args()
    points = table_points()
    data = read_levels()
    fine = read_fine_levels([p for p in args.fine_levels.split(",") if p])
    if args.fine_check:
        fine_check(data, fine, points, args.fit_from, args.fine_from, args.fine_check)
        return
    if not args.table_only:
        levels = [int(x) for x in args.levels.split(",")]
        ratios = [float(x) for x in args.ratios.split(",")] if args.ratios else None
        nus = [float(x) for x in args.nu.split(",")]
        todo = [(r, nu) for r, nu in points
                if nu in nus and (ratios is None or any(abs(r - x) < 1e-5 * x for x in ratios))]
        todo.sort(key=lambda p: max(p[0], 1 / p[0]))     # cheap (round) ellipses first
        t0 = time.time()
        for r, nu in todo:
            for N in levels:
                if N in data.get(key(r, nu), {}):
                    continue
                if time.time() - t0 > args.max_seconds:
                    print("time budget used; run again to continue", file=sys.stderr)
                    break
                d = K.ellipse_level(r, nu, N)
                append_level(r, nu, N, d)
                data.setdefault(key(r, nu), {})[N] = d
                print(f"a/b {r:.4g} nu {nu:g} N {N}: {d['mx']} x {d['my']}, {d['time']:.1f} s", file=sys.stderr)
    if not os.path.exists(args.out):
        shutil.copyfile(TABLE_FILE, args.out)
    for rounds in range(1, 11):
        with open(args.out) as f:
            before = f.read()
        rows = write_table(data, points, args.fit_from, fine, args.fine_from, args.out)
        with open(args.out) as f:
            if f.read() == before:
                break
    print(f"{len(rows)} of {len(points)} points in {args.out} ({rounds} rounds)")


if __name__ == "__main__":
    main()
