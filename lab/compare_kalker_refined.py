#!/usr/bin/env python3
"""Kalker's three-digit table E3 against the refined table (docs/data/kalker_refined.dat).

    compare_kalker_refined.py [--markdown]

Prints, per a/b and nu, Kalker's C11, C22, C23, the refined values with their
uncertainty and the relative difference Kalker - refined (%), then the median
and worst differences; --markdown prints the summary table for docs/accuracy.md.
"""
import sys as _sys

if __name__ == "__main__" and any(a in ("-h", "--help") for a in _sys.argv[1:]):
    print("usage: lab/compare_kalker_refined.py\n" + __doc__)
    _sys.exit(0)
import os
import statistics
import sys

sys.path[:0] = [os.path.join(os.path.dirname(os.path.abspath(__file__)), d) for d in (".", "../tools/maintenance", "../scripts/convergence", "../tests/calibration")]
import refine_kalker_table as R  # noqa: E402
import kcreep_levels as K  # noqa: E402


def main():
    md = "--markdown" in sys.argv
    ref = {R.key(float(r["a_over_b"]), float(r["nu"])): r for r in K.read_table(R.TABLE_FILE)}
    diffs = {c: [] for c in ("c11", "c22", "c23")}
    lines = []
    for r, nu, kal in R.kalker_points():
        row = ref.get(R.key(r, nu))
        if row is None:
            continue
        parts = [f"{r:7.4g} {nu:4g}"]
        for c in ("c11", "c22", "c23"):
            v, u = float(row[c]), float(row["u" + c[1:]])
            d = 100 * (kal[c] / v - 1)
            diffs[c].append((abs(d), d, r, nu, 100 * u / v))
            parts.append(f"{kal[c]:6.3g} {v:8.5g} +-{100 * u / v:5.3f}% {d:+6.2f}%")
        lines.append("  ".join(parts))
    if md:
        print("| coefficient | points | median abs(Kalker/refined - 1) | worst (a/b, nu) | median u of the refined value |")
        print("|---|---|---|---|---|")
        for c, v in diffs.items():
            worst = max(v)
            print(f"| {c.upper()} | {len(v)} | {statistics.median(x[0] for x in v):.2f} % | "
                  f"{worst[1]:+.2f} % ({worst[2]:g}, {worst[3]:g}) | {statistics.median(x[4] for x in v):.3f} % |")
    else:
        print("# a_over_b nu  Kalker refined +-u difference  for C11, C22, C23")
        print("\n".join(lines))


if __name__ == "__main__":
    main()
