#!/usr/bin/env python3
"""Two grids per level for ellipses long in x: does their mean carry less
staircase noise? (docs/accuracy.md section 6.3)

    /usr/bin/python3 lab/offset_pair_study.py [--ratio 5] [--nu 0.25] [--levels 112,128,...,296]

For each level N (cells across the shorter axis b, square cells) the
ellipse a = sqrt(ratio), b = 1/sqrt(ratio) is solved on two grids that are
both symmetric in x and y: kcreep's own (cell centres at half-multiples of
dx from the centre) and the one shifted by dx/2 with one more column (cell
centres at multiples of dx). Each is written as a mask file and solved by
build/kcreep (method 'iterative', tolerance 1e-7, spin about the centroid);
each level is referred to the ellipse by its staircase's second moments
(as kcreep_staircase_normalisation), with its four-fold harmonic. Printed:
per coefficient, the fit f0 + K h + B harmonic4 through the levels of
either grid and through the mean of the two, with t95 x its standard error
of f0 (the part of kcreep's estimate that limits ellipses long in x) and
the rms scatter about the fit. --also-y adds the grid shifted by dy/2 (one
more row) and the grid shifted both ways. Needs numpy (/usr/bin/python3).
"""
import argparse
import math
import os
import subprocess
import sys
import tempfile

if __name__ == "__main__" and any(a in ("-h", "--help") for a in sys.argv[1:]):
    print(__doc__)
    sys.exit(0)
import numpy as np  # noqa: E402

sys.path[:0] = [os.path.join(os.path.dirname(os.path.abspath(__file__)), d) for d in (".", "../tools/maintenance", "../scripts/convergence", "../tests/calibration")]
import kcreep_levels as K  # noqa: E402
from kcreep_levels import student_t95  # noqa: E402

POWERS = {"c11": 2, "c22": 2, "c23": 3}


def level(ratio, nu, cells, shifted, slopes, folder, y_shifted=False):
    """One grid's coefficients referred to the ellipse, and its harmonic
    (shifted: by dx/2 with one more column; y_shifted: by dy/2 with one more row)."""
    a, b = math.sqrt(ratio), 1 / math.sqrt(ratio)
    my = cells + (1 if y_shifted else 0)
    mx0 = int(round(2 * a / (2 * b / cells)))
    dx, dy = 2 * a / mx0, 2 * b / cells
    mx = mx0 + (1 if shifted else 0)
    x0 = -a + dx / 2 - (dx / 2 if shifted else 0)
    y0 = -b + dy / 2 - (dy / 2 if y_shifted else 0)
    x, y = np.meshgrid(x0 + dx * np.arange(mx), y0 + dy * np.arange(my))
    inside = (x / a) ** 2 + (y / b) ** 2 <= 1
    with open(os.path.join(folder, "level.mask"), "w") as f:
        f.write(f"{mx} {my} {dx!r} {dy!r} {x0!r} {y0!r}\n")
        for row in inside:
            f.write("".join("#" if v else "." for v in row) + "\n")
    with open(os.path.join(folder, "level.nml"), "w") as f:
        f.write(f"&patch shape = 'mask', mask_file = 'level.mask' /\n&material nu = {nu!r} /\n"
                "&solver method = 'iterative', target_error = 0, tolerance = 1e-7, spin_centre = 'centroid' /\n"
                "&output table_file = 'level.tab' /\n")
    subprocess.run([K.KCREEP, "level.nml"], cwd=folder, check=True, capture_output=True)
    row = K.read_table(os.path.join(folder, "level.tab"))[-1]
    xi, yi = x[inside], y[inside]
    ixx = ((xi - xi.mean()) ** 2).mean() + dx * dx / 12
    iyy = ((yi - yi.mean()) ** 2).mean() + dy * dy / 12
    a_s, b_s = 2 * math.sqrt(ixx), 2 * math.sqrt(iyy)
    xn, yn = (xi - xi.mean()) / a, (yi - yi.mean()) / b
    out = {"harmonic4": float((xn ** 4 - 6 * xn ** 2 * yn ** 2 + yn ** 4).sum() * (dx / a) * (dy / b))}
    log_scale, log_aspect = 0.5 * math.log(1 / (a_s * b_s)), math.log((a_s / b_s) / ratio)
    for c, f in (("c11", "f11"), ("c22", "f22"), ("c23", "f23")):
        out[c] = float(row[f]) / float(row["g"]) * math.exp(POWERS[c] * log_scale - slopes[c] * log_aspect)
    return out


def fit(cells, values, harmonic):
    h = np.array([1.0 / n for n in cells])
    a = np.array([np.ones_like(h), h, harmonic]).T
    coef = np.linalg.lstsq(a, values, rcond=None)[0]
    r = values - a @ coef
    dof = len(cells) - 3
    se = math.sqrt(r @ r / dof * np.linalg.inv(a.T @ a)[0, 0])
    return coef[0], student_t95(dof) * se / coef[0], math.sqrt((r ** 2).mean()) / coef[0]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--ratio", type=float, default=5.0)
    ap.add_argument("--nu", type=float, default=0.25)
    ap.add_argument("--levels", default="112,128,148,172,196,224,256,296")
    ap.add_argument("--also-y", action="store_true",
                    help="also the grid shifted by dy/2 (one more row): the y pair and the mean of all four grids")
    args = ap.parse_args()
    cells = [int(n) for n in args.levels.split(",")]
    slopes = K.table_slopes(args.ratio, args.nu)
    folder = tempfile.mkdtemp(prefix="kcreep-offset-")
    grids = ((False, False), (True, False)) + (((False, True), (True, True)) if args.also_y else ())
    levels = {n: [level(args.ratio, args.nu, n, sx, slopes, folder, sy) for sx, sy in grids] for n in cells}
    print(f"a/b = {args.ratio:g}, nu = {args.nu:g}, levels {args.levels}")
    print("| coefficient | grids | f0 | t95 x SE of f0 | rms scatter |")
    print("|---|---|---|---|---|")
    for c in ("c11", "c22", "c23"):
        picks = [("kcreep's", lambda p: (p[0][c], p[0]["harmonic4"])),
                 ("shifted by dx/2", lambda p: (p[1][c], p[1]["harmonic4"])),
                 ("mean of the two", lambda p: ((p[0][c] + p[1][c]) / 2, (p[0]["harmonic4"] + p[1]["harmonic4"]) / 2))]
        if args.also_y:
            picks += [("mean with the dy/2 grid", lambda p: ((p[0][c] + p[2][c]) / 2,
                                                           (p[0]["harmonic4"] + p[2]["harmonic4"]) / 2)),
                      ("mean of all four", lambda p: (sum(q[c] for q in p) / 4, sum(q["harmonic4"] for q in p) / 4))]
        for name, pick in picks:
            values = np.array([pick(levels[n])[0] for n in cells])
            harmonic = np.array([pick(levels[n])[1] for n in cells])
            f0, se, rms = fit(cells, values, harmonic)
            print(f"| {c.upper()} | {name} | {f0:.6f} | {100 * se:.4f} % | {100 * rms:.4f} % |")


if __name__ == "__main__":
    main()
