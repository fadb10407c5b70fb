#!/usr/bin/env python3
"""Richardson extrapolation of kcreep tables in the mesh size.

    richardson.py TABLE [--min-ratio 1.5]

Rows are grouped into series by their case name without the trailing
'_m<M>' (the study scripts name cases that way). The mesh size of a row is
h = 1/sqrt(mx my), so grids with non-square cells and rounded cell counts
are handled. For every triple of meshes h1 > h2 > h3 in a series with about
the same refinement ratio (h1/h2 and h2/h3 both >= --min-ratio and within
10 % of each other), and for each of c11, c22, c23, the model
f(h) = f0 + K h^p is fitted through the three points: p is the observed
order, f0 the extrapolated limit. When the two differences have opposite
signs the sequence is not in its asymptotic range: p and f0 are NaN.
Ellipse series appear twice: as computed, and as '<series>@area' with the
coefficients normalised by the staircase patch's own area (c^2 = area/pi),
which removes the irregular change of the staircase area with the mesh.

Output: one line per series, triple and coefficient (whitespace columns,
'#' header), read by the study scripts and tools/maintenance/make_report.py.
"""
import argparse
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "python"))
from kcreep import table  # noqa: E402  (standard library only)


def read_table(path):
    """Rows as dicts of strings (the callers convert what they need)."""
    return table.read(path, numbers=False)


def area_factor(row):
    """(exact ellipse area) / (staircase area) of an ellipse row: the grid spans
    [-a, a] x [-b, b], so a cell has area 4ab/(mx my), and ab = c^2."""
    return math.pi * float(row["mx"]) * float(row["my"]) / (4 * float(row["n"]))


def area_normalised(row):
    """The row with C11, C22 (C23) normalised by the staircase's own c^2 (c^3),
    c = sqrt(area/pi), as for a mask: what kcreep's extrapolate does on ellipses."""
    q = area_factor(row)
    out = dict(row)
    out["c11"] = str(float(row["c11"]) * q)
    out["c22"] = str(float(row["c22"]) * q)
    out["c23"] = str(float(row["c23"]) * q**1.5)
    return out


def observed_order(h, f):
    """p with (f1-f2)/(f2-f3) = (h1^p-h2^p)/(h2^p-h3^p), by bisection; None if none."""
    d1, d2 = f[0] - f[1], f[1] - f[2]
    if d2 == 0 or d1 == 0 or (d1 > 0) != (d2 > 0):
        return None
    target = d1 / d2

    def g(p):
        return (h[0] ** p - h[1] ** p) / (h[1] ** p - h[2] ** p) - target

    lo, hi = 0.02, 12.0
    if g(lo) * g(hi) > 0:
        return None
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if g(lo) * g(mid) <= 0:
            hi = mid
        else:
            lo = mid
    return 0.5 * (lo + hi)


def extrapolate(h, f, p):
    """f0 of f = f0 + K h^p through the two finest points."""
    k = (f[1] - f[2]) / (h[1] ** p - h[2] ** p)
    return f[2] - k * h[2] ** p


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("table")
    ap.add_argument("--min-ratio", type=float, default=1.5)
    ap.add_argument("--series-key", default=None, help="(informational) how case names are built")
    args = ap.parse_args()

    series = {}
    for row in read_table(args.table):
        name = os.path.basename(row["case"])
        key, _, m = name.rpartition("_m")
        if not key or not m.isdigit():
            continue
        h = 1 / math.sqrt(float(row["mx"]) * float(row["my"]))
        series.setdefault(key, []).append((h, int(m), row))
        if row.get("klt11", "NaN").lower() != "nan":
            series.setdefault(key + "@area", []).append((h, int(m), area_normalised(row)))

    print("# Richardson extrapolation f(h) = f0 + K h^p through three meshes, h = 1/sqrt(mx my)")
    print("# p: observed order (nan: differences change sign, not asymptotic); f0: limit;")
    print("# err3: |f0 - f(finest)| / f0 (estimated error of the finest mesh); klt: Kalker;")
    print("# f0_vs_klt_pct: 100 (f0/klt - 1), the limit against Kalker in percent")
    print("# series M1 M2 M3 coef f1 f2 f3 p f0 err3 klt f0_vs_klt_pct")
    for key in sorted(series):
        pts = sorted(series[key], key=lambda t: -t[0])
        for i in range(len(pts)):
            for j in range(i + 1, len(pts)):
                for k in range(j + 1, len(pts)):
                    h = [pts[i][0], pts[j][0], pts[k][0]]
                    r1, r2 = h[0] / h[1], h[1] / h[2]
                    if r1 < args.min_ratio or r2 < args.min_ratio or abs(r1 / r2 - 1) > 0.1:
                        continue
                    for coef in ("c11", "c22", "c23"):
                        f = [float(pts[q][2][coef]) for q in (i, j, k)]
                        klt = float(pts[k][2]["klt" + coef[1:]])
                        p = observed_order(h, f)
                        if p is None:
                            p = f0 = err = float("nan")
                        else:
                            f0 = extrapolate(h, f, p)
                            err = abs(f0 - f[2]) / abs(f0)
                        vs = f0 / klt - 1 if klt == klt else float("nan")
                        print(f"{key} {pts[i][1]} {pts[j][1]} {pts[k][1]} {coef} "
                              f"{f[0]:.6f} {f[1]:.6f} {f[2]:.6f} {p:.3f} {f0:.6f} {err:.2e} {klt:.4f} {vs:+.4%}"
                              .replace("%", ""))


if __name__ == "__main__":
    sys.exit(main())
