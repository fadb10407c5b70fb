#!/usr/bin/env python3
"""The refined Kalker table as the reference of the convergence studies.

    scripts/convergence/refined_reference.py RATIO NU [--table FILE]
        print 'c11 u11 c22 u22 c23 u23' of the node a/b = RATIO, nu = NU
    scripts/convergence/refined_reference.py --help
        this text

The table is docs/data/kalker_refined.dat (tools/maintenance/refine_kalker_table.sh;
docs/accuracy.md, "The refined table of ellipses"): kcreep's backward scheme on levels of 56 to 196
cells across (at the fine rows of section 5.2, 296 to 632-1024), fitted
f0 + K h + B harmonic4, with u the absolute 95 % uncertainty of each value. Only nodes of the table are served: a study at an a/b or nu that is
not a node gets an error naming the nodes (interpolating in a/b would add
an error of its own that the reference's u does not cover).
The study scripts (sweep_alpha.sh, sweep_n.sh, error_vs_time.sh) and
tools/maintenance/make_report.py use it; importable as a module (node, load).
"""
import os
import sys

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(REPO, "python"))
from kcreep import table  # noqa: E402  (standard library only)

TABLE = os.path.join(REPO, "docs", "data", "kalker_refined.dat")
COEFS = ("c11", "c22", "c23")


def load(path=TABLE):
    """{(a_over_b, nu): {'c11': value, 'u11': u, ...}} of every row."""
    return {(w["a_over_b"], w["nu"]): w for w in table.read(path)}


def node(ratio, nu, path=TABLE):
    """The row of the node (ratio, nu); LookupError when it is not a node.
    A node matches to 1e-4 relative in a/b (the table prints 1/0.9 as 1.11111)
    and 1e-9 in nu."""
    rows = load(path)
    for (r, n), w in rows.items():
        if abs(r / ratio - 1) <= 1e-4 and abs(n - nu) <= 1e-9:
            return w
    ratios = sorted({r for r, _ in rows})
    nus = sorted({n for _, n in rows})
    raise LookupError(f"{os.path.basename(path)}: a/b = {ratio:g}, nu = {nu:g} is not a node of the refined "
                      f"table (a/b: {' '.join(f'{r:g}' for r in ratios)}; nu: {' '.join(f'{n:g}' for n in nus)}); "
                      "the studies use nodes only, no interpolation")


def main(args):
    if any(a in ("-h", "--help") for a in args):
        print(__doc__.strip())
        return 0
    path = TABLE
    if "--table" in args:
        i = args.index("--table")
        if i + 1 >= len(args):
            print("refined_reference.py: error: --table needs a file name", file=sys.stderr)
            return 2
        path = args[i + 1]
        args = args[:i] + args[i + 2:]
    if len(args) != 2:
        print("refined_reference.py: error: usage: refined_reference.py RATIO NU [--table FILE] (see --help)",
              file=sys.stderr)
        return 2
    try:
        ratio, nu = float(args[0]), float(args[1])
    except ValueError:
        print(f"refined_reference.py: error: RATIO and NU must be numbers (got {args[0]!r} {args[1]!r})",
              file=sys.stderr)
        return 2
    if not ratio > 0:
        print(f"refined_reference.py: error: RATIO = {ratio:g}: allowed a/b > 0", file=sys.stderr)
        return 2
    try:
        w = node(ratio, nu, path)
    except (LookupError, OSError, ValueError, KeyError) as e:
        print(f"refined_reference.py: error: {e}", file=sys.stderr)
        return 2
    print(" ".join(f"{w[c]:.6g} {w['u' + c[1:]]:.6g}" for c in COEFS))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
