#!/usr/bin/env python3
"""Errors and run times of the error_vs_time study.

    scripts/convergence/error_vs_time.py RUNS_TABLE [--ratio 1] [--nu 0.25]
                                          (scripts/convergence/error_vs_time.sh calls it)
    scripts/convergence/error_vs_time.py --help       this text

Case names are <scheme>_rep<k>_m<M> (M x M grid, or about M*M near-square
cells) and default_rep<k>_m0, accurate_rep<k>_m0: kcreep's own choice of
grids under error control (only semi_a, semi_b and nu given; accurate:
target_error = 1e-4); their M is the finest grid kcreep reached.
Per scheme and mesh: the fastest of the repeats' times (kcreep's t_total,
which includes its error estimate; the fastest, because on a shared machine
the other runs measure the other work as well) and the coefficients
(identical in every repeat).

Reference: the refined Kalker table (docs/data/kalker_refined.dat, through
scripts/convergence/refined_reference.py: a/b and nu must be one of its nodes) with its
95 % uncertainty u, printed in the header ('# reference' lines). Errors are
relative, err = |C/C_ref - 1|; u/C_ref is the level below which an error
cannot be told from the reference's own uncertainty. Rows
<scheme>+extrapolate: what &solver extrapolate = .true. gives from the
levels M/4, M/2, M (the formula of src/pipeline/kcreep_extrapolation.f90;
time: the sum of the three runs). est11 est22 est23: kcreep's own estimate
of its relative error (the err columns of its table; NaN when it has none).
The deviations from Kalker's three-digit table are given beside them.
"""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from richardson import read_table, area_normalised  # noqa: E402
from refined_reference import node  # noqa: E402

COEFS = ("c11", "c22", "c23")
CONTROLLED = ("default", "accurate")


def option(args, name, default):
    if name in args:
        i = args.index(name)
        if i + 1 >= len(args):
            sys.exit(f"error_vs_time.py: error: {name} needs a value")
        value = args[i + 1]
        del args[i:i + 2]
        try:
            return float(value)
        except ValueError:
            sys.exit(f"error_vs_time.py: error: {name} = {value!r}: a number is needed")
    return default


def main():
    args = sys.argv[1:]
    if any(a in ("-h", "--help") for a in args):
        print(__doc__.strip())
        return 0
    ratio = option(args, "--ratio", 1.0)
    nu = option(args, "--nu", 0.25)
    if len(args) != 1:
        sys.exit("usage: error_vs_time.py RUNS_TABLE [--ratio R] [--nu NU] (see --help)")
    try:
        refrow = node(ratio, nu)
    except LookupError as e:
        sys.exit(f"error_vs_time.py: error: {e}")
    rows = read_table(args[0])
    runs = {}
    for row in rows:
        scheme, rep, m = os.path.basename(row["case"]).split("_")
        runs.setdefault((scheme, int(m[1:])), []).append(row)
    order = ("collocation", "backward") + CONTROLLED
    schemes = sorted({s for s, _ in runs}, key=lambda s: order.index(s) if s in order else len(order))

    ref = {c: refrow[c] for c in COEFS}
    unc = {c: refrow["u" + c[1:]] for c in COEFS}
    klt = {c: float(rows[0]["klt" + c[1:]]) for c in COEFS}
    print(f"# error against run time, a/b = {ratio:g}, nu = {nu:g}; reference: the refined Kalker table "
          "(docs/data/kalker_refined.dat)")
    for c in COEFS:
        print(f"# reference {c} = {ref[c]:.6g} +- {unc[c]:.3g} ({100 * unc[c] / ref[c]:.3f} %); "
              f"Kalker {klt[c]:.3f} ({100 * (klt[c] / ref[c] - 1):+.2f} %)")
    print("# err*: |C/C_ref - 1|; klt*: C/C_Kalker - 1; t: fastest t_total of the repeats [s];")
    print("# est*: kcreep's estimated relative error; M: grid M x M (default, accurate: finest grid reached)")
    print("# scheme M n t c11 c22 c23 err11 err22 err23 klt11 klt22 klt23 repeats est11 est22 est23 verdict")

    def line(name, m, n, t, c, repeats, est, verdict):
        err = [abs(c[i] / ref[k] - 1) for i, k in enumerate(COEFS)]
        vk = [c[i] / klt[k] - 1 for i, k in enumerate(COEFS)]
        print(f"{name} {m} {n} {t:.4f} " + " ".join(f"{x:.6f}" for x in c) + " "
              + " ".join(f"{x:.3e}" for x in err) + " " + " ".join(f"{x:+.3e}" for x in vk)
              + f" {repeats} " + " ".join(f"{x:.3e}" for x in est) + f" {verdict}")

    for scheme in schemes:
        for m in sorted(mm for s, mm in runs if s == scheme):
            group = runs[(scheme, m)]
            r = group[0]
            t = min(float(g["t_total"]) for g in group)
            line(scheme, int(r["mx"]) if scheme in CONTROLLED else m, r["n"], t,
                 [float(r[k]) for k in COEFS], len(group), [float(r["err" + k[1:]]) for k in COEFS], r["verdict"])
    # what &solver extrapolate = .true. gives (3 levels M/4, M/2, M, ratio 2)
    for scheme in schemes:
        if scheme in CONTROLLED:
            continue
        meshes = sorted(m for s, m in runs if s == scheme)
        for m in meshes:
            triple = (m // 4, m // 2, m)
            if m % 4 or triple[0] not in meshes or triple[1] not in meshes:
                continue
            t = sum(min(float(g["t_total"]) for g in runs[(scheme, mm)]) for mm in triple)
            c = [kcreep_extrapolation([float(area_normalised(runs[(scheme, mm)][0])[k]) for mm in triple])
                 for k in COEFS]
            line(scheme + "+extrapolate", m, runs[(scheme, m)][0]["n"], t, c, len(runs[(scheme, m)]),
                 [float("nan")] * 3, "-")
    return 0


def kcreep_extrapolation(f, ratio=2.0):
    """The limit src/pipeline/kcreep_extrapolation.f90 reports for three levels."""
    d1, d2 = f[1] - f[0], f[2] - f[1]
    p = 1.0
    if d1 != 0 and d2 != 0 and (d1 > 0) == (d2 > 0):
        q = math.log(d1 / d2) / math.log(ratio)
        if 0.5 <= q <= 3:
            p = q
    return f[2] + (f[2] - f[1]) / (ratio**p - 1)


if __name__ == "__main__":
    sys.exit(main())
