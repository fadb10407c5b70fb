#!/usr/bin/env python3
"""Errors and run times of the error_vs_time study.

    scripts/error_vs_time.py RUNS_TABLE    (scripts/error_vs_time.sh calls it)
    scripts/error_vs_time.py --help        this text

Case names are <scheme>_rep<k>_m<M>. Per scheme and mesh: the median wall
time over the repeats (t_total) and the coefficients (identical in every
repeat). Reference: each scheme's Richardson limit through its three finest
meshes M/4, M/2, M, each normalised by its staircase area (as kcreep's
extrapolate does); the reference is the mean of the two schemes' limits,
half their difference its uncertainty. Errors are relative, |C/C_ref - 1|;
rows <scheme>+extrapolate: what &solver extrapolate = .true. gives from
M/4, M/2, M (time: the sum of the three runs);
the errors against Kalker's three-digit table are given beside them.
"""
import math
import os
import statistics
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from richardson import read_table, observed_order, extrapolate, area_normalised  # noqa: E402

COEFS = ("c11", "c22", "c23")


def main():
    if any(a in ("-h", "--help") for a in sys.argv[1:]):
        print(__doc__.strip())
        return 0
    if len(sys.argv) != 2:
        sys.exit("usage: error_vs_time.py RUNS_TABLE (see --help)")
    rows = read_table(sys.argv[1])
    runs = {}
    for row in rows:
        scheme, rep, m = row["case"].split("_")
        runs.setdefault((scheme, int(m[1:])), []).append(row)
    schemes = sorted({s for s, _ in runs}, key=lambda s: s != "collocation")

    limits = {}
    for scheme in schemes:
        meshes = sorted(m for s, m in runs if s == scheme)
        triple = None
        for m3 in reversed(meshes):
            if m3 % 4 == 0 and m3 // 2 in meshes and m3 // 4 in meshes:
                triple = (m3 // 4, m3 // 2, m3)
                break
        if triple is None:
            sys.exit(f"error_vs_time.py: no meshes M/4, M/2, M for {scheme}: cannot extrapolate")
        for coef in COEFS:
            h, f = [], []
            for m in triple:
                r = area_normalised(runs[(scheme, m)][0])
                h.append(1 / math.sqrt(float(r["mx"]) * float(r["my"])))
                f.append(float(r[coef]))
            p = observed_order(h, f)
            if p is None or not 0.5 <= p <= 3:
                # no believable order: first order, as kcreep's extrapolate does (printed as p = 1*)
                f0 = kcreep_extrapolation(f)
                p = float("nan")
            else:
                f0 = extrapolate(h, f, p)
            limits[(scheme, coef)] = (triple, p, f0)

    ref, unc = {}, {}
    any_row = next(iter(runs.values()))[0]
    klt = {c: float(any_row["klt" + c[1:]]) for c in COEFS}
    print("# error against run time; reference = mean of the Richardson limits of the schemes")
    for coef in COEFS:
        values = [limits[(s, coef)][2] for s in schemes]
        ref[coef] = statistics.fmean(values)
        unc[coef] = (max(values) - min(values)) / 2 / abs(ref[coef])
        parts = ", ".join(f"{s} {limits[(s, coef)][2]:.5f} (p = {fmt_order(limits[(s, coef)][1])}, meshes "
                          f"{'/'.join(map(str, limits[(s, coef)][0]))})" for s in schemes)
        print(f"# reference {coef} = {ref[coef]:.5f} +- {100 * unc[coef]:.2f} %  [{parts}]; "
              f"Kalker {klt[coef]:.3f} ({100 * (klt[coef] / ref[coef] - 1):+.2f} %)")
    print("# p = 1*: the three meshes show no order in [0.5, 3]; first order assumed")
    print("# err*: |C/C_ref - 1|; klt*: C/C_Kalker - 1; t_med: median wall time of the runs [s]")
    print("# scheme M n t_med c11 c22 c23 err11 err22 err23 klt11 klt22 klt23 repeats")
    for scheme in schemes:
        for m in sorted(mm for s, mm in runs if s == scheme):
            group = runs[(scheme, m)]
            r = group[0]
            t = statistics.median(float(g["t_total"]) for g in group)
            c = [float(r[k]) for k in COEFS]
            err = [abs(c[i] / ref[k] - 1) for i, k in enumerate(COEFS)]
            vk = [c[i] / klt[k] - 1 for i, k in enumerate(COEFS)]
            print(f"{scheme} {m} {r['n']} {t:.4f} " + " ".join(f"{x:.6f}" for x in c) + " "
                  + " ".join(f"{x:.3e}" for x in err) + " " + " ".join(f"{x:+.3e}" for x in vk)
                  + f" {len(group)}")
    # what &solver extrapolate = .true. gives (3 levels M/4, M/2, M, ratio 2; the
    # same formula as src/extrapolation.f90), for every M whose finest-triple is
    # not the reference's own (that one would be compared with itself)
    for scheme in schemes:
        meshes = sorted(m for s, m in runs if s == scheme)
        ref_triple = limits[(scheme, COEFS[0])][0]
        for m in meshes:
            triple = (m // 4, m // 2, m)
            if m % 4 or triple[0] not in meshes or triple[1] not in meshes or triple == ref_triple:
                continue
            t = sum(statistics.median(float(g["t_total"]) for g in runs[(scheme, mm)]) for mm in triple)
            c = []
            for k in COEFS:
                f = [float(area_normalised(runs[(scheme, mm)][0])[k]) for mm in triple]
                c.append(kcreep_extrapolation(f))
            err = [abs(c[i] / ref[k] - 1) for i, k in enumerate(COEFS)]
            vk = [c[i] / klt[k] - 1 for i, k in enumerate(COEFS)]
            n = runs[(scheme, m)][0]["n"]
            print(f"{scheme}+extrapolate {m} {n} {t:.4f} " + " ".join(f"{x:.6f}" for x in c) + " "
                  + " ".join(f"{x:.3e}" for x in err) + " " + " ".join(f"{x:+.3e}" for x in vk)
                  + f" {len(runs[(scheme, m)])}")


def fmt_order(p):
    return "1*" if p != p else f"{p:.2f}"


def kcreep_extrapolation(f, ratio=2.0):
    """The limit src/extrapolation.f90 reports for three levels."""
    d1, d2 = f[1] - f[0], f[2] - f[1]
    p = 1.0
    if d1 != 0 and d2 != 0 and (d1 > 0) == (d2 > 0):
        q = math.log(d1 / d2) / math.log(ratio)
        if 0.5 <= q <= 3:
            p = q
    return f[2] + (f[2] - f[1]) / (ratio**p - 1)


if __name__ == "__main__":
    sys.exit(main())
