#!/usr/bin/python3
"""The aspect-ratio slopes d ln C / d ln(a/b) beyond the refined table
(a/b > 10): differences between solved ellipses (method 'iterative', the
default target) against the slope kcreep uses there (the table's slope at
a/b = 10 continued linearly in ln(a/b), held from a/b = 20;
kcreep_staircase_normalisation aspect_slopes). docs/accuracy.md section 3.

  OMP_NUM_THREADS=1 flock /tmp/kcreep-bench.lock /usr/bin/python3 lab/long_ellipse_slopes.py

Needs numpy and build/libkcreep; about 15 s on one core.
"""
import argparse
import math
import os
import sys

RATIOS = (8.0, 10.0, 12.0, 14.0, 17.0, 20.0)
STEP, BASE, LIMIT = 0.01, 0.3, 20.0   # as in aspect_slopes


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--nu", type=float, default=0.28, help="Poisson's ratio (default 0.28)")
    args = parser.parse_args()
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "python"))
    import numpy as np
    import kcreep

    def table_c(ratio):
        return np.log(kcreep.solve_ellipse(ratio, 1.0, nu=args.nu, method="table").c[:3])

    def table_slope(lo, hi):
        return (table_c(hi) - table_c(lo)) / math.log(hi / lo)

    edge = table_slope(10.0 * math.exp(-STEP), 10.0)
    below = table_slope(10.0 * math.exp(-BASE - STEP), 10.0 * math.exp(-BASE))

    def used_slope(ratio):
        return edge + (edge - below) / BASE * math.log(min(ratio, LIMIT) / 10.0)

    solved = {}
    for ratio in RATIOS:
        result = kcreep.solve_ellipse(ratio, 1.0, nu=args.nu, method="iterative")
        solved[ratio] = result
        print(f"a/b {ratio:g}: {result.verdict}, C11 C22 C23 {np.round(result.c[:3], 5)}, estimates %"
              f" {np.round(100 * np.asarray(result.err[:3]), 3)}")
    print("| between a/b | at | solved slope C11 / C22 / C23 | kcreep's slope | held at a/b = 10 |")
    print("|---|---|---|---|---|")
    fmt = lambda v: " / ".join(f"{x:.4f}" for x in v)  # noqa: E731
    for lo, hi in zip(RATIOS[:-1], RATIOS[1:]):
        mid = math.sqrt(lo * hi)
        slope = (np.log(solved[hi].c[:3]) - np.log(solved[lo].c[:3])) / math.log(hi / lo)
        used = used_slope(mid) if mid > 10 else table_slope(mid * math.exp(-STEP), min(mid * math.exp(STEP), 10.0))
        print(f"| {lo:g}-{hi:g} | {mid:.2f} | {fmt(slope)} | {fmt(used)} | {fmt(edge)} |")


if __name__ == "__main__":
    main()
