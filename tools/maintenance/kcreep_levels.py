#!/usr/bin/env python3
"""Run kcreep on an ellipse at given resolutions and extrapolate (standard library only).

Shared by tools/maintenance/refine_kalker_table.py, lab/accuracy_table.py and the
error-control tests. An ellipse with semi-axes a = sqrt(r), b = 1/sqrt(r)
(c = sqrt(ab) = 1, r = a/b) is put on a grid of near-square cells with
`cells` cells across its shorter axis. The coefficients are normalised by the
area of the cells inside the ellipse (c^2 = staircase area / pi): that is what
makes the backward scheme converge cleanly at first order (docs/convergence.md).
refer_to_ellipse() then takes out the staircase's aspect ratio as well, as
kcreep's own levels do (src/coefficients/kcreep_staircase_normalisation.f90).
"""
import sys as _sys

if __name__ == "__main__" and any(a in ("-h", "--help") for a in _sys.argv[1:]):
    print("usage: tools/maintenance/kcreep_levels.py\n" + __doc__)
    _sys.exit(0)
import math
import os
import re
import subprocess
import tempfile

_sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "python"))
from kcreep import table as kcreep_table  # noqa: E402  (standard library only)

KCREEP = os.environ.get("KCREEP", os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "build", "kcreep"))
# the grid exactly as given, without the one-grid error estimate's extra grid
# (set KCREEP_TARGET_ZERO='' for a kcreep older than &solver target_error)
TARGET_ZERO = os.environ.get("KCREEP_TARGET_ZERO", ", target_error = 0")
COEFFS = ("c11", "c22", "c23", "c33", "c32")
# powers of c in each normalised coefficient (c11 = f11/(G c^2), c23 = f23/(G c^3), c33 = f33/(G c^4))
POWERS = {"c11": 2, "c22": 2, "c23": 3, "c33": 4, "c32": 3}


def _t95_of_the_library():
    """Student's table and its tail as kcreep_refine_estimate.student_t95 has
    them, read from that source: the one place they are written."""
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "src", "refine",
                        "kcreep_refine_estimate.f90")
    text = open(path).read()
    body = text[text.index("function student_t95"):text.index("end function student_t95")]
    table = tuple(float(x) for x in re.findall(r"([\d.]+)_real64", body[body.index("table(") :body.index("]")]))
    tail = re.search(r"t = ([\d.]+)_real64 \+ ([\d.]+)_real64 / dof", body)
    return table, float(tail.group(1)), float(tail.group(2))


def student_t95(dof):
    """Two-sided 95 % Student factor of kcreep_refine_estimate.student_t95 (dof >= 1)."""
    table, base, slope = _T95
    return table[dof - 1] if dof <= len(table) else base + slope / dof


_T95 = _t95_of_the_library()


def square_grid(ratio, cells, grid="near-square"):
    """(mx, my) with `cells` cells across the shorter axis: near-square cells,
    or with grid = 'box' on an ellipse long in y (ratio < 1) cells x cells,
    the cells long in y (as kcreep's levels for tight targets,
    kcreep_refine_estimate.ellipse_cells_long_in_y)."""
    if ratio >= 1:
        return int(round(cells * ratio)), cells
    if grid == "box":
        return cells, cells
    return cells, int(round(cells / ratio))


def read_table(path):
    """Rows as dicts of strings (the callers convert what they need)."""
    return kcreep_table.read(path, numbers=False)


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


def ellipse_level(ratio, nu, cells, scheme="backward", method="iterative", extra_solver=TARGET_ZERO, kcreep=None,
                  grid="near-square"):
    """Area-normalised coefficients of one grid (square_grid's grid): dict with c11 ... c32, mx, my, n, time,
    iterations."""
    a, b = math.sqrt(ratio), 1 / math.sqrt(ratio)
    mx, my = square_grid(ratio, cells, grid)
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


def read_level_file(path):
    """{(a_over_b, nu): {N: level}} of a levels file (columns a_over_b nu N mx my
    n c11 c22 c23 c33 c32, further columns ignored; the coefficients as stored,
    normalised by the staircase area as ellipse_level gives them); {} when the
    file does not exist."""
    data = {}
    if not os.path.exists(path):
        return data
    with open(path) as f:
        for line in f:
            if line.startswith("#") or not line.strip():
                continue
            p = line.split()
            level = {"mx": int(p[3]), "my": int(p[4]), "n": int(p[5])}
            level.update(dict(zip(COEFFS, map(float, p[6:11]))))
            data.setdefault((float(p[0]), float(p[1])), {})[int(p[2])] = level
    return data


def staircase_moments(ratio, mx, my):
    """(a_s, b_s, harmonic4) of the ellipse a = sqrt(ratio), b = 1/sqrt(ratio) on
    an mx x my grid: the semi-axes of the ellipse with the staircase's second
    moments (cells with their own dx^2/12), and its four-fold harmonic
    sum (X^4 - 6 X^2 Y^2 + Y^4) dX dY in X = x/a, Y = y/b (cell centres).
    Row by row: a row's cells inside are one run of columns, found with the
    cell test of kcreep_patch (centre inside), and the power sums over the run
    are exact integer sums (X = u / mx, u = 2 i + 1 - mx), so the fine levels
    (up to 10 million cells) take milliseconds."""
    a, b = math.sqrt(ratio), 1 / math.sqrt(ratio)
    dx, dy = 2 * a / mx, 2 * b / my
    n = 0
    sxx = syy = h4 = 0.0
    for j in range(my):
        y = (-b + dy * (j + 0.5)) / b
        lo, hi = _inside_run(a, dx, mx, y)
        if lo > hi:
            continue
        count = hi - lo + 1
        u0 = 2 * lo + 1 - mx
        s2 = _step2_power_sum(u0, count, 2) / mx ** 2
        s4 = _step2_power_sum(u0, count, 4) / mx ** 4
        n += count
        sxx += s2
        syy += count * y * y
        h4 += s4 - 6 * y * y * s2 + count * y ** 4
    ixx = (sxx * a * a + n * dx * dx / 12) / n
    iyy = (syy * b * b + n * dy * dy / 12) / n
    return 2 * math.sqrt(ixx), 2 * math.sqrt(iyy), h4 * (dx / a) * (dy / b)


def _inside_run(a, dx, mx, y):
    """First and last column of a row whose centres lie inside (lo > hi: none)."""
    def inside(i):
        x = (-a + dx * (i + 0.5)) / a
        return 0 <= i < mx and x * x + y * y <= 1
    half = math.sqrt(max(0.0, 1 - y * y)) * mx / 2      # about half the run, in cells
    lo, hi = int(math.floor(mx / 2 - half)), int(math.ceil(mx / 2 + half))
    while lo > 0 and inside(lo - 1):
        lo -= 1
    while lo <= hi and not inside(lo):
        lo += 1
    while hi < mx - 1 and inside(hi + 1):
        hi += 1
    while hi >= lo and not inside(hi):
        hi -= 1
    return lo, hi


def _step2_power_sum(u0, count, p):
    """sum of (u0 + 2 k)^p for k = 0 .. count - 1, exactly (integers)."""
    m = count - 1
    k_sums = [count, m * (m + 1) // 2, m * (m + 1) * (2 * m + 1) // 6, (m * (m + 1) // 2) ** 2,
              m * (m + 1) * (2 * m + 1) * (3 * m * m + 3 * m - 1) // 30]
    return sum(math.comb(p, q) * u0 ** (p - q) * 2 ** q * k_sums[q] for q in range(p + 1))


def table_slopes(ratio, nu, table=None):
    """d ln C / d ln(a/b) of c11 c22 c23 c33 c32 from the refined table (central
    differences between its rows, linear in ln(a/b) between them; linear in nu
    between the table's nu columns, a nu outside them clamped)."""
    table = table or os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "docs", "data",
                                  "kalker_refined.dat")
    columns = {}
    with open(table) as f:
        for line in f:
            if line.startswith("#") or not line.strip():
                continue
            p = [float(x) for x in line.split()]
            columns.setdefault(p[1], {})[p[0]] = dict(zip(COEFFS, (p[2], p[4], p[6], p[8], p[10])))
    nus = sorted(columns)
    nu = min(max(nu, nus[0]), nus[-1])
    k = max(i for i in range(len(nus)) if nus[i] <= nu)
    if nus[k] == nu or k == len(nus) - 1:
        return _slopes_at(columns[nus[k]], ratio)
    w = (nu - nus[k]) / (nus[k + 1] - nus[k])
    s0, s1 = _slopes_at(columns[nus[k]], ratio), _slopes_at(columns[nus[k + 1]], ratio)
    return {c: (1 - w) * s0[c] + w * s1[c] for c in COEFFS}


def _slopes_at(rows, ratio):
    """The slopes of one nu column {a/b: {coefficient: value}} at ratio."""
    rs = sorted(rows)
    r = min(max(ratio, rs[0]), rs[-1])

    def at_row(i):
        lo, hi = rs[max(i - 1, 0)], rs[min(i + 1, len(rs) - 1)]
        return {k: math.log(rows[hi][k] / rows[lo][k]) / math.log(hi / lo) for k in COEFFS}
    i = max(k for k in range(len(rs)) if rs[k] <= r)
    if i == len(rs) - 1:
        return at_row(i)
    w = math.log(r / rs[i]) / math.log(rs[i + 1] / rs[i])
    s0, s1 = at_row(i), at_row(i + 1)
    return {k: (1 - w) * s0[k] + w * s1[k] for k in COEFFS}


def refer_to_ellipse(ratio, nu, level, slopes=None):
    """An area-normalised level (ellipse_level's dict) referred to the ellipse by
    its second moments: size as c^p, aspect ratio by the table's slopes. Adds
    'harmonic4'. Returns a new dict."""
    slopes = slopes or table_slopes(ratio, nu)
    a_s, b_s, h4 = staircase_moments(ratio, level["mx"], level["my"])
    area_c2 = math.pi * level["mx"] * level["my"] / (4 * level["n"])   # (c / c_area)^2, c = 1
    log_scale = 0.5 * math.log(1 / (a_s * b_s))                                     # ln(c / c_moments)
    log_aspect = math.log((a_s / b_s) / ratio)
    out = dict(level)
    for k in COEFFS:
        raw = level[k] / area_c2 ** (POWERS[k] / 2)
        out[k] = raw * math.exp(POWERS[k] * log_scale - slopes[k] * log_aspect)
    out["harmonic4"] = h4
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
