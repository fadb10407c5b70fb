#!/usr/bin/env python3
"""Order of convergence of the mesh study, measured against the refined table.

    scripts/convergence/convergence_order.py SWEEP_TABLE [--nu 0.25]   (sweep_n.sh calls it)
    scripts/convergence/convergence_order.py --help                    this text

SWEEP_TABLE: the merged table of scripts/convergence/sweep_n.sh (cases
r<ratio>_<grid>_<scheme>_m<M>). For each series and coefficient C11, C22,
C23, the relative error e(M) = C(M)/C_ref - 1 against the refined Kalker
table (scripts/convergence/refined_reference.py: nodes only), with each mesh's
coefficients normalised by the area of its staircase (c^2 = area/pi, as
kcreep's error control does), which removes the staircase's irregular area
error and leaves the method's own error. Printed per series:

  p       least-squares slope of log|e| against log M over the meshes
          M = 20 ... 80 (first order: p = 1; an h log h term: p < 1 and
          rising with M); '-' when e changes sign there
  p range p with the reference moved by -u and +u (its 95 % uncertainty)
  eM20, eM80  e times M at M = 20 and the finest mesh: constant for a
          first-order error, growing like log M for h log h
  +-      how much of the change eM80 - eM20 the reference's u can explain
          ((M_last - 20) u/C_ref)
"""
import math
import os
import sys

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, here)
from richardson import read_table, area_normalised  # noqa: E402
from refined_reference import node  # noqa: E402

COEFS = ("c11", "c22", "c23")
FIT_MESHES = (20, 30, 40, 60, 80)


def series(rows):
    """{(ratio, grid, scheme): {M: row}} of the sweep_n table's rows."""
    out = {}
    for r in rows:
        ratio, grid, scheme, m = os.path.basename(r["case"]).split("_")
        out.setdefault((float(ratio[1:]), grid, scheme), {})[int(m[1:])] = r
    return out


def rel_error(row, coef, ref, area=True):
    """C/C_ref - 1 of one row, normalised by its staircase area when area is true."""
    r = area_normalised(row) if area else row
    return float(r[coef]) / ref - 1


def slope(ms, errs):
    """Least-squares p of |e| = A M^-p; nan when e changes sign or vanishes."""
    if len(ms) < 2 or any(e == 0 for e in errs) or len({e > 0 for e in errs}) > 1:
        return float("nan")
    x = [math.log(m) for m in ms]
    y = [math.log(abs(e)) for e in errs]
    xm, ym = sum(x) / len(x), sum(y) / len(y)
    return -sum((a - xm) * (b - ym) for a, b in zip(x, y)) / sum((a - xm) ** 2 for a in x)


def order(by_mesh, coef, refrow):
    """The order summary of one series and coefficient (see the module text)."""
    ref, u = refrow[coef], refrow["u" + coef[1:]]
    ms = [m for m in FIT_MESHES if m in by_mesh]
    if len(ms) < 3:
        return None
    e = {m: rel_error(by_mesh[m], coef, ref) for m in ms}
    p = slope(ms, [e[m] for m in ms])
    shifted = [slope(ms, [rel_error(by_mesh[m], coef, ref + s * u) for m in ms]) for s in (-1, 1)]
    lo, hi = min(shifted), max(shifted)
    if lo != lo or hi != hi:
        lo = hi = float("nan")
    first, last = ms[0], ms[-1]
    return dict(p=p, p_lo=lo, p_hi=hi, m_first=first, m_last=last, e_first=e[first], e_last=e[last],
                em_first=e[first] * first, em_last=e[last] * last, em_u=(last - first) * u / ref, u_rel=u / ref)


def fmt(x, spec):
    return "-" if x != x else format(x, spec)


def main(args):
    if any(a in ("-h", "--help") for a in args):
        print(__doc__.strip())
        return 0
    nu = 0.25
    if "--nu" in args:
        i = args.index("--nu")
        nu = float(args[i + 1])
        args = args[:i] + args[i + 2:]
    if len(args) != 1:
        print("convergence_order.py: error: usage: convergence_order.py SWEEP_TABLE [--nu NU] (see --help)",
              file=sys.stderr)
        return 2
    all_series = series(read_table(args[0]))
    print("# order against the refined table (area-normalised coefficients, meshes "
          + "/".join(map(str, FIT_MESHES)) + ")")
    print("# series coef ref u_rel p p_lo p_hi eM_first eM_last eM_u")
    for key in sorted(all_series):
        ratio, grid, scheme = key
        try:
            refrow = node(ratio, nu)
        except LookupError as e:
            print(f"convergence_order.py: error: {e}", file=sys.stderr)
            return 2
        for coef in COEFS:
            o = order(all_series[key], coef, refrow)
            if o is None:
                continue
            print(f"r{ratio:g}_{grid}_{scheme} {coef} {refrow[coef]:.6g} {o['u_rel']:.2e} {fmt(o['p'], '.3f')} "
                  f"{fmt(o['p_lo'], '.3f')} {fmt(o['p_hi'], '.3f')} {o['em_first']:+.4f} {o['em_last']:+.4f} "
                  f"{o['em_u']:.4f}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
