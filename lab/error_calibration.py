#!/usr/bin/env python3
"""How often kcreep's error estimate bounds the true error (the calibration behind
kcreep_refine_estimate), from the levels in lab/data/error_calibration_levels.dat.

    error_calibration.py [--reference-levels 56,64,96,128]

For each ellipse (a/b 0.1 ... 10, nu 0, 0.25, 0.5) the reference is the
least-squares fit c0 + K h through the finest levels (--reference-levels,
those present), with its 95 % interval u. The estimators, on coarser levels:
  levels 16-48 (8):  kcreep's default set 16, 20, 24, 28, 32, 36, 40, 48
  levels 16-48 (4):  16, 24, 32, 48
  levels 24-64 (8), 32-64 (5): finer sets
each: limit = the first-order fit, estimate = t95(dof) x standard error.
  one grid N (two-grid estimate, target_error = 0): 2 |f(N) - f(N/2)| / f + area error.
Counts: estimate >= |limit - ref| (and the same allowing the reference's u).
"""
import argparse
import math
import os
import statistics

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
import sys  # noqa: E402
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tools", "maintenance"))
from kcreep_levels import student_t95  # noqa: E402  (the library's table)
POW = {"c11": 2, "c22": 2, "c23": 3}


def fit(Ns, fs):
    hs = [1 / N for N in Ns]
    m = len(hs)
    hm, fm = sum(hs) / m, sum(fs) / m
    shh = sum((h - hm) ** 2 for h in hs)
    k = sum((h - hm) * (f - fm) for h, f in zip(hs, fs)) / shh
    f0 = fm - k * hm
    if m <= 2:
        return f0, float("nan"), 0
    s2 = sum((f - f0 - k * h) ** 2 for h, f in zip(hs, fs)) / (m - 2)
    return f0, math.sqrt(s2 * (1 / m + hm ** 2 / shh)), m - 2


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--reference-levels", default="56,64,96,128")
    args = ap.parse_args()
    data = {}
    with open(os.path.join(ROOT, "lab", "data", "error_calibration_levels.dat")) as f:
        for line in f:
            if line.startswith("#"):
                continue
            p = line.split()
            data.setdefault((float(p[0]), float(p[1])), {})[int(p[2])] = {
                "mx": int(p[3]), "my": int(p[4]), "n": int(p[5]), "c11": float(p[6]), "c22": float(p[7]),
                "c23": float(p[8])}
    refN = [int(x) for x in args.reference_levels.split(",")]
    sets = {"levels 16-48 (8, default)": [16, 20, 24, 28, 32, 36, 40, 48], "levels 16-48 (4)": [16, 24, 32, 48],
            "levels 24-64 (8)": [24, 28, 32, 36, 40, 48, 56, 64], "levels 32-64 (5)": [32, 40, 48, 56, 64]}
    print("| estimator | coefficient | cases | bounded | bounded allowing u | median error | worst error | median estimate |")
    print("|---|---|---|---|---|---|---|---|")
    for name, S in list(sets.items()) + [(f"one grid N = {N}", N) for N in (24, 32, 48)]:
        for c in ("c11", "c22", "c23"):
            n = b = bu = 0
            errs, ests = [], []
            for key, lv in sorted(data.items()):
                rn = [N for N in refN if N in lv]
                if len(rn) < 3:
                    continue
                ref, se, dof = fit(rn, [lv[N][c] for N in rn])
                u = student_t95(dof) * se / abs(ref)
                if isinstance(S, list):
                    if not all(N in lv for N in S):
                        continue
                    f0, s, d = fit(S, [lv[N][c] for N in S])
                    err, est = abs(f0 - ref) / abs(ref), student_t95(d) * s / abs(f0)
                else:
                    N = S
                    if N not in lv or N // 2 not in lv:
                        continue
                    x, y = lv[N], lv[N // 2]
                    q = (math.pi * x["mx"] * x["my"] / (4 * x["n"])) ** (POW[c] / 2)
                    err = abs(x[c] / q - ref) / abs(ref)
                    est = 2 * abs(x[c] - y[c]) / abs(x[c]) + abs(q - 1)
                n += 1
                b += est >= err
                bu += est + u >= err
                errs.append(err)
                ests.append(est)
            print(f"| {name} | {c.upper()} | {n} | {b} | {bu} | {100 * statistics.median(errs):.3f} % | "
                  f"{100 * max(errs):.3f} % | {100 * statistics.median(ests):.3f} % |")


if __name__ == "__main__":
    main()
