#!/usr/bin/env python3
"""Check kcreep's stated errors against an independent reference.

    independent_check.py [--cases 1:0.25,0.5:0.25,...] [--levels 136,152,160,...,384] [--max-cells 200000]
                         [--cache FILE] [--target T] [--cell-budget CELLS] [--tolerance T] [--restart R]
                         [--markdown] [--out FILE]

For each case (a/b : nu; ellipse with c = sqrt(ab) = 1) kcreep is run twice
with only semi_a, semi_b, nu given:

    solved  &solver method = 'iterative': the levels kcreep chooses (56 to at
            most about 150 cells across), its estimates err11 err22 err23
    table   &solver method = 'table': the refined table, interpolated (most
            cases lie between its rows and columns), its stated uncertainty

With --target T the solved run gets &solver target_error = T (T = 1e-4: the
accurate mode, levels to about 300 cells across) and the verdict is shown;
--cell-budget sets &solver cell_budget (the finest level's cells) with it.

The reference comes from grids much finer than either uses (--levels, cells
across the shorter axis, as far as the grid's mx x my <= --max-cells; --grid box
puts them, for a/b < 1, on N x N grids with cells long in y, as kcreep's own
levels for tight targets), each referred
to the ellipse by the staircase's second moments (kcreep_levels.refer_to_ellipse)
and fitted by f0 + K h + B harmonic4; its uncertainty u is the larger of the
fit's 95 % interval (Student's t) and the change of f0 when an h^2 term is
added (as the refined table's u). The reference levels are kept in
lab/data/independent_reference_levels.dat (--cache) and reused (delete it
to recompute: about 25 minutes on one core). The accurate mode's check uses
grids of 256 to 2048 cells across, kept in tools/maintenance/data/fine_reference_levels.dat
(about 90 minutes on one core):

    independent_check.py --cache tools/maintenance/data/fine_reference_levels.dat --target 1e-4 \
        --cases 1:0.25,1:0.5,2:0.25,0.5:0.25,4:0.25,0.25:0.25 \
        --levels 256,296,340,384,448,512,576,640,768,896,1024 --max-cells 1.1e6
Printed
per coefficient: each answer's error against the reference, its stated error,
and whether that bounds the error (also allowing u). Standard library only.
"""
import argparse
import math
import os
import sys

sys.path[:0] = [os.path.join(os.path.dirname(os.path.abspath(__file__)), d) for d in (".", "../tools/maintenance", "../scripts/convergence", "../tests/calibration")]
import kcreep_levels as K  # noqa: E402
from refine_kalker_table import lstsq_columns  # noqa: E402

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
CACHE = os.path.join(ROOT, "lab", "data", "independent_reference_levels.dat")
DEFAULT_CASES = ("1:0.25,1:0,1:0.5,0.5:0.25,2:0.25,0.667:0.25,1.5:0.25,0.7:0.25,1.43:0.5,0.25:0,4:0.5,"
                 "1:0.3,0.667:0.1,1.5:0.45,0.3:0.2")
COLUMNS = ["a_over_b", "nu", "N", "mx", "my", "n"] + list(K.COEFFS)


def append_cache(cache, ratio, nu, n, level):
    new = not os.path.exists(cache)
    with open(cache, "a") as f:
        if new:
            f.write("# reference levels of lab/independent_check.py: ellipse c = 1, backward scheme, N cells across\n"
                    "# the shorter axis, coefficients normalised by the staircase area (as kcreep_levels.ellipse_level)\n"
                    "# " + " ".join(COLUMNS) + "\n")
        f.write(f"{ratio:g} {nu:g} {n} {level['mx']} {level['my']} {level['n']} " +
                " ".join(f"{level[c]:.12e}" for c in K.COEFFS) + "\n")


def reference(levels, ratio, nu):
    """{coefficient: (f0, u)} from the fine levels."""
    slopes = K.table_slopes(ratio, nu)
    ns = sorted(levels)
    referred = [K.refer_to_ellipse(ratio, nu, levels[n], slopes) for n in ns]
    columns = [[1.0] * len(ns), [1.0 / n for n in ns], [x["harmonic4"] for x in referred]]
    quadratic = columns + [[1.0 / n ** 2 for n in ns]]
    out = {}
    for c in ("c11", "c22", "c23"):
        values = [x[c] for x in referred]
        f0, se, dof = lstsq_columns(columns, values)
        f0_quadratic = lstsq_columns(quadratic, values)[0]
        out[c] = (f0, max(K.student_t95(dof) * se, abs(f0_quadratic - f0)))
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--cases", default=DEFAULT_CASES)
    ap.add_argument("--levels", default="136,152,160,184,216,240,272,304,344,384")
    ap.add_argument("--max-cells", type=float, default=2.0e5)
    ap.add_argument("--cache", default=CACHE, help="the reference levels file (read and appended to)")
    ap.add_argument("--target", type=float, default=0.0, help="&solver target_error of the solved run (0: its default)")
    ap.add_argument("--cell-budget", type=float, default=0.0, help="&solver cell_budget of the solved run")
    ap.add_argument("--grid", choices=("near-square", "box"), default="near-square",
                    help="the reference levels' cells: near-square, or for a/b < 1 N x N over the bounding box "
                         "(cells long in y, as kcreep's levels for tight targets); keep each in its own --cache")
    ap.add_argument("--tolerance", type=float, default=0.0, help="&solver tolerance of the reference levels (0: kcreep's)")
    ap.add_argument("--restart", type=int, default=0,
                    help="&solver restart of the reference levels (0: kcreep's; smaller needs less memory)")
    ap.add_argument("--markdown", action="store_true")
    ap.add_argument("--out", default="")
    args = ap.parse_args()
    levels = [int(x) for x in args.levels.split(",")]
    cases = [tuple(float(v) for v in c.split(":")) for c in args.cases.split(",")]
    cache = K.read_level_file(args.cache)
    target = f", target_error = {args.target!r}" if args.target > 0 else ""
    if args.cell_budget > 0:
        target += f", cell_budget = {args.cell_budget!r}"
    lines = ["| a/b | nu | coefficient | reference (u) | solved: error / estimate | table: error / stated | "
             "solved: finest grid, verdict, wall time |", "|---|---|---|---|---|---|---|"]
    counts = {"solved": [0, 0, 0], "table": [0, 0, 0]}      # bounded, bounded allowing u, cases
    for ratio, nu in cases:
        have = cache.setdefault((ratio, nu), {})
        for n in levels:
            mx, my = K.square_grid(ratio, n, args.grid)
            if n not in have and mx * my <= args.max_cells:
                extra = K.TARGET_ZERO + (f", tolerance = {args.tolerance!r}" if args.tolerance > 0 else "")
                extra += f", restart = {args.restart}" if args.restart > 0 else ""
                have[n] = K.ellipse_level(ratio, nu, n, grid=args.grid, extra_solver=extra)
                append_cache(args.cache, ratio, nu, n, have[n])
        ref = reference({n: v for n, v in have.items() if n in levels}, ratio, nu)
        a, b = math.sqrt(ratio), 1 / math.sqrt(ratio)
        rows, walls = {}, {}
        # the refined table covers 0.1 <= a/b <= 10 (kcreep refuses method = 'table' beyond)
        in_table = 0.1 <= ratio <= 10
        for name, method in (("solved", "iterative"), ("table", "table")):
            if name == "table" and not in_table:
                continue
            nml = (f"&patch shape = 'ellipse', semi_a = {a!r}, semi_b = {b!r} /\n&material nu = {nu!r} /\n"
                   f"&solver method = '{method}'{target if name == 'solved' else ''} /\n"
                   f"&output table_file = 'case.tab' /\n")
            table_rows, walls[name], _ = K.run_kcreep(nml)
            rows[name] = table_rows[-1]
        for c, e in (("c11", "err11"), ("c22", "err22"), ("c23", "err23")):
            f0, u = ref[c]
            cells = []
            for name in ("solved", "table"):
                if name not in rows:
                    cells.append("outside the table")
                    continue
                value, stated = float(rows[name][c]), float(rows[name][e])
                err = abs(value / f0 - 1)
                counts[name][0] += stated >= err
                counts[name][1] += stated + u / abs(f0) >= err
                counts[name][2] += 1
                cells.append(f"{100 * err:.3f} / {100 * stated:.3f} %" + ("" if stated >= err else " (not bounded)"))
            lines.append(f"| {ratio:g} | {nu:g} | {c.upper()} | {f0:.5f} ({100 * u / abs(f0):.3f} %) | "
                         f"{cells[0]} | {cells[1]} | {rows['solved']['mx']} x {rows['solved']['my']}, "
                         f"{rows['solved']['verdict']}, {walls['solved']:.1f} s |")
            print(lines[-1], flush=True)
    lines.append("")
    for name in ("solved", "table"):
        b, bu, n = counts[name]
        lines.append(f"{name}: the stated error bounded the error in {b} of {n} coefficients ({bu} allowing the "
                     f"reference's u).")
        print(lines[-1])
    lines.append(f"Reference levels {args.levels} cells across, {args.grid} cells (grid cells <= {args.max_cells:g}).")
    if args.out:
        with open(args.out, "w") as f:
            f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    if any(a in ("-h", "--help") for a in sys.argv[1:]):
        print("usage: lab/independent_check.py [options]\n" + __doc__)
        sys.exit(0)
    main()
