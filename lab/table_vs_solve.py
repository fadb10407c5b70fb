#!/usr/bin/env python3
"""method = 'table' against solves between the table's rows and columns.

    table_vs_solve.py [--markdown]

For a fixed set of ellipses between the refined table's rows and columns
(a/b from 0.15 to 7, nu between 0.05 and 0.45), runs kcreep twice: with
&solver method = 'table', and with method = 'iterative' (a solve under error control,
target 1e-3). Prints per point the relative difference of C11 C22 C23
between the two and the sum of the two stated errors (table uncertainty +
the solve's estimate); the two agree when the difference is within that sum.
About half a minute on 2 cores. KCREEP (environment) names the binary
(default build/kcreep). Standard library only.
"""
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "python"))
from kcreep import table  # noqa: E402

KCREEP = os.environ.get("KCREEP", os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "build", "kcreep"))
POINTS = [(0.15, 0.1), (0.25, 0.4), (0.45, 0.2), (0.75, 0.35), (1.2, 0.05), (1.8, 0.45), (2.9, 0.3),
          (4.2, 0.15), (7.0, 0.4)]
COEFFS = (("c11", "err11"), ("c22", "err22"), ("c23", "err23"))


def run(folder, name, ratio, nu, solver):
    a, b = ratio ** 0.5, ratio ** -0.5
    path = os.path.join(folder, name + ".nml")
    with open(path, "w") as f:
        f.write(f"&patch shape = 'ellipse', semi_a = {a!r}, semi_b = {b!r} /\n&material nu = {nu!r} /\n"
                f"&solver {solver} /\n")
    proc = subprocess.run([KCREEP, name + ".nml"], cwd=folder, capture_output=True, text=True)
    if proc.returncode != 0:
        sys.exit(f"table_vs_solve.py: kcreep failed on a/b = {ratio}, nu = {nu}: {proc.stderr.strip()}")
    return table.read(os.path.join(folder, name + ".tab"))[0]


def main():
    if any(a in ("-h", "--help") for a in sys.argv[1:]):
        print(__doc__.strip())
        return
    markdown = "--markdown" in sys.argv[1:]
    folder = tempfile.mkdtemp(prefix="kcreep-table-vs-solve-")
    rows, agree, total = [], 0, 0
    for k, (ratio, nu) in enumerate(POINTS):
        t = run(folder, f"table{k}", ratio, nu, "method = 'table'")
        s = run(folder, f"solve{k}", ratio, nu, "method = 'iterative'")
        cells = []
        for c, e in COEFFS:
            diff = abs(t[c] / s[c] - 1)
            allowed = t[e] + s[e]
            agree += diff <= allowed
            total += 1
            cells.append((diff, t[e], s[e]))
        rows.append((ratio, nu, cells, s["t_total"]))
    if markdown:
        print("| a/b | nu | C11: diff / table + solve | C22 | C23 | solve [s] |")
        print("|---|---|---|---|---|---|")
        for ratio, nu, cells, seconds in rows:
            text = " | ".join(f"{100 * d:.3f} / {100 * te:.2f} + {100 * se:.2f} %" for d, te, se in cells)
            print(f"| {ratio:g} | {nu:g} | {text} | {seconds:.2f} |")
    else:
        for ratio, nu, cells, seconds in rows:
            print(f"a/b {ratio:5g} nu {nu:4g}: " + "  ".join(
                f"{c}: {100 * d:.3f} % (table {100 * te:.2f} + solve {100 * se:.2f} %)"
                for (c, _), (d, te, se) in zip(COEFFS, cells)))
    print(f"{agree} of {total} differences within the sum of the stated errors")
    for name in os.listdir(folder):
        os.remove(os.path.join(folder, name))
    os.rmdir(folder)


if __name__ == "__main__":
    main()
