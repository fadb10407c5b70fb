#!/usr/bin/python3
"""Solved ellipses a/b = 0.1 to 10 at the default target (docs/accuracy.md
section 3): each ellipse solved by kcreep's levels (method 'iterative', the
library's default call otherwise) against the refined table (method
'table', its stated uncertainty u printed beside), with verdict, estimate,
error against the table and wall time.

  OMP_NUM_THREADS=1 flock /tmp/kcreep-bench.lock /usr/bin/python3 lab/solved_ellipse_check.py
  ... --nus 0,0.25,0.5    each ratio at these Poisson's ratios, and how many estimates bound their errors

Needs numpy and build/libkcreep; about 7 s on one core.
"""
import argparse
import os
import sys
import time

RATIOS = (0.1, 0.2, 0.5, 1.0, 2.0, 3.33, 5.0, 10.0)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--target", type=float, default=1e-3, help="target_error (default 1e-3)")
    parser.add_argument("--ratios", type=float, nargs="+", default=RATIOS, help="a/b values (default 0.1 to 10)")
    parser.add_argument("--nus", default="0.25", help="Poisson's ratios, comma-separated (default 0.25)")
    args = parser.parse_args()
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "python"))
    import numpy as np
    import kcreep
    print("| a/b | nu | verdict | estimate C11 / C22 / C23 % | error against the table % | table u % | wall s |")
    print("|---|---|---|---|---|---|---|")
    bounded, ratios = 0, []
    for nu in (float(v) for v in args.nus.split(",")):
        for ratio in args.ratios:
            start = time.perf_counter()
            solved = kcreep.solve_ellipse(ratio, 1.0, nu=nu, method="iterative", target_error=args.target)
            wall = time.perf_counter() - start
            table = kcreep.solve_ellipse(ratio, 1.0, nu=nu, method="table")
            error = np.abs(solved.c / table.c - 1)
            bounded += int(np.sum(error <= solved.err))
            ratios += list(solved.err / np.maximum(error, 1e-12))
            fmt = lambda v: " / ".join(f"{100 * x:.3f}" for x in v)  # noqa: E731
            print(f"| {ratio:g} | {nu:g} | {solved.verdict} | {fmt(solved.err)} | {fmt(error)} | {fmt(table.err)} "
                  f"| {wall:.2f} |")
    print(f"\n{bounded} of {len(ratios)} estimates above the error against the table; median estimate / error "
          f"{np.median(ratios):.1f}")


if __name__ == "__main__":
    main()
