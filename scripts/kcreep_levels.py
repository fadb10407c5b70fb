#!/usr/bin/env python3
"""Run kcreep on an ellipse at given resolutions and extrapolate (standard library only).

Shared by scripts/refine_kalker_table.py, scripts/accuracy_table.py and the
error-control tests. An ellipse with semi-axes a = sqrt(r), b = 1/sqrt(r)
(c = sqrt(ab) = 1, r = a/b) is put on a grid of near-square cells with
`cells` cells across its shorter axis. The coefficients are normalised by the
area of the cells inside the ellipse (c^2 = staircase area / pi): that is what
makes the backward scheme converge cleanly at first order (docs/convergence.md).
"""
import sys as _sys

if __name__ == "__main__" and any(a in ("-h", "--help") for a in _sys.argv[1:]):
    print("usage: scripts/kcreep_levels.py\n" + __doc__)
    _sys.exit(0)
import math
import os
import subprocess
import tempfile

KCREEP = os.environ.get("KCREEP", os.path.join(os.path.dirname(__file__), "..", "build", "kcreep"))
# the grid exactly as given, without the one-grid error estimate's extra grid
# (set KCREEP_TARGET_ZERO='' for a kcreep older than &solver target_error)
TARGET_ZERO = os.environ.get("KCREEP_TARGET_ZERO", ", target_error = 0")
COEFFS = ("c11", "c22", "c23", "c33", "c32")
# powers of c in each normalised coefficient (c11 = f11/(G c^2), c23 = f23/(G c^3), c33 = f33/(G c^4))
POWERS = {"c11": 2, "c22": 2, "c23": 3, "c33": 4, "c32": 3}


def square_grid(ratio, cells):
    """(mx, my) with near-square cells and `cells` cells across the shorter axis."""
    if ratio >= 1:
        return int(round(cells * ratio)), cells
    return cells, int(round(cells / ratio))


def read_table(path):
    columns, rows = None, []
    with open(path) as f:
        for line in f:
            if line.startswith("#"):
                columns = line[1:].split()
                continue
            if line.strip():
                rows.append(dict(zip(columns, line.split())))
    return rows


def run_kcreep(nml_text, name="case", kcreep=None, folder=None):
    """Run kcreep on a namelist; return (table rows, wall time, stderr)."""
    import time
    own = folder is None
    folder = folder or tempfile.mkdtemp(prefix="kcreep-levels-")
    path = os.path.join(folder, name + ".nml")
    with open(path, "w") as f:
        f.write(nml_text)
    t0 = time.perf_counter()
    proc = subprocess.run([kcreep or KCREEP, name + ".nml"], cwd=folder, capture_output=True, text=True)
    wall = time.perf_counter() - t0
    if proc.returncode != 0:
        raise RuntimeError(f"kcreep failed ({proc.returncode}): {proc.stderr.strip()}")
    rows = read_table(os.path.join(folder, name + ".tab"))
    if own:
        for fn in os.listdir(folder):
            os.remove(os.path.join(folder, fn))
        os.rmdir(folder)
    return rows, wall, proc.stderr


def ellipse_level(ratio, nu, cells, scheme="backward", method="iterative", extra_solver=TARGET_ZERO, kcreep=None):
    """Area-normalised coefficients of one grid: dict with c11 ... c32, mx, my, n, time, iterations."""
    a, b = math.sqrt(ratio), 1 / math.sqrt(ratio)
    mx, my = square_grid(ratio, cells)
    nml = (f"&patch shape = 'ellipse', semi_a = {a!r}, semi_b = {b!r}, mx = {mx}, my = {my} /\n"
           f"&material nu = {nu!r} /\n"
           f"&solver scheme = '{scheme}', method = '{method}' {extra_solver} /\n"
           f"&output table_file = 'case.tab' /\n")
    rows, wall, _ = run_kcreep(nml, kcreep=kcreep)
    row = rows[-1]
    n = int(row["n"])
    q = math.pi * mx * my / (4 * n)          # exact area / staircase area (c = 1)
    out = {"mx": mx, "my": my, "n": n, "time": wall, "iterations": int(row.get("iterations", 0))}
    g, c = float(row["g"]), float(row["c"])
    for k in COEFFS:
        v = float(row[k]) if k in ("c11", "c22", "c23") else float(row["f" + k[1:]]) / (g * c ** POWERS[k])
        out[k] = v * q ** (POWERS[k] / 2)
    return out


def richardson(values, hs, order=1.0):
    """Limit of f(h) = f0 + K1 h + K2 h^2 + ... through the given levels with the
    orders fixed (1, 2, ...): two levels eliminate h, three levels h and h^2."""
    m = len(values)
    # solve the Vandermonde-like system f_i = f0 + sum_k K_k h_i^(k*order)
    A = [[1.0] + [h ** (order * (k + 1)) for k in range(m - 1)] for h in hs]
    return solve(A, list(values))[0]


def solve(A, b):
    n = len(b)
    M = [row[:] + [b[i]] for i, row in enumerate(A)]
    for c in range(n):
        p = max(range(c, n), key=lambda r: abs(M[r][c]))
        M[c], M[p] = M[p], M[c]
        for r in range(n):
            if r != c:
                f = M[r][c] / M[c][c]
                for k in range(c, n + 1):
                    M[r][k] -= f * M[c][k]
    return [M[i][n] / M[i][i] for i in range(n)]
