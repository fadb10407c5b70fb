#!/usr/bin/env python3
"""Check the default run's error estimate against an independent reference.

    independent_check.py [--cases 1:0.25,0.5:0.25,...] [--levels 216,240,272,304,344,384]
                         [--solver "target_error = 1e-3"] [--markdown] [--out FILE]

For each case (a/b : nu; ellipse with c = sqrt(ab) = 1) kcreep's default run
(only semi_a, semi_b, nu given, plus --solver) gives C11, C22, C23 and its
estimates err11 err22 err23. The reference is computed from grids much finer
than any the default run uses (--levels, cells across the shorter axis; the
default run stops below 230 across within its cell budget), each normalised
by its staircase area, fitted by f0 + K h, with its 95 % interval u
(Student's t). Printed per coefficient: the default run's error against the
reference, its estimate, u, and whether the estimate bounds the error (and
whether it does allowing u). Standard library only; a few minutes per case
on 2 cores (the reference grids have up to 116,000 cells per unit of a/b).
"""
import argparse
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import kcreep_levels as K  # noqa: E402
from refine_kalker_table import T95, lstsq  # noqa: E402

DEFAULT_CASES = "1:0.25,0.5:0.25,2:0.25,0.667:0.25,1.5:0.25,1:0,1:0.5"


def fit(hs, fs):
    """f0 of the least-squares line f0 + K h and the 95 % half-width of f0."""
    f0, std_error, dof = lstsq(hs, fs, (1,))
    return f0, T95[dof] * std_error


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--cases", default=DEFAULT_CASES)
    ap.add_argument("--levels", default="216,240,272,304,344,384")
    ap.add_argument("--solver", default="")
    ap.add_argument("--markdown", action="store_true")
    ap.add_argument("--out", default="")
    args = ap.parse_args()
    levels = [int(x) for x in args.levels.split(",")]
    cases = [tuple(float(v) for v in c.split(":")) for c in args.cases.split(",")]
    lines = ["| a/b | nu | coefficient | default value | error against reference | estimate | reference u | "
             "bounded | bounded allowing u | default finest grid |", "|---|---|---|---|---|---|---|---|---|---|"]
    bounded = within_u = total = 0
    for ratio, nu in cases:
        a, b = math.sqrt(ratio), 1 / math.sqrt(ratio)
        nml = (f"&patch shape = 'ellipse', semi_a = {a!r}, semi_b = {b!r} /\n&material nu = {nu!r} /\n"
               f"&solver {args.solver} /\n&output table_file = 'case.tab' /\n")
        row = K.run_kcreep(nml)[0][-1]
        fine = [K.ellipse_level(ratio, nu, n) for n in levels]
        for c, e in (("c11", "err11"), ("c22", "err22"), ("c23", "err23")):
            ref, u = fit([1 / n for n in levels], [f[c] for f in fine])
            value, est = float(row[c]), float(row[e])
            err = abs(value - ref) / abs(ref)
            rel_u = u / abs(ref)
            total += 1
            bounded += est >= err
            within_u += est + rel_u >= err
            lines.append(f"| {ratio:g} | {nu:g} | {c.upper()} | {value:.5f} | {100 * err:.3f} % | {100 * est:.3f} % | "
                         f"{100 * rel_u:.3f} % | {'yes' if est >= err else 'no'} | "
                         f"{'yes' if est + rel_u >= err else 'no'} | {row['mx']} x {row['my']} |")
            print(lines[-1], flush=True)
    lines.append("")
    lines.append(f"The estimate bounded the error in {bounded} of {total} coefficients ({within_u} allowing the "
                 f"reference's u); reference levels {args.levels} cells across.")
    print(lines[-1])
    if args.out:
        with open(args.out, "w") as f:
            f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    if any(a in ("-h", "--help") for a in sys.argv[1:]):
        print("usage: scripts/independent_check.py [options]\n" + __doc__)
        sys.exit(0)
    main()
