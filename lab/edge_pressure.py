#!/usr/bin/python3
"""The normal problem's pressure near the contact edge against Hertz's
(docs/normal.md, kcreep_region edge_blend): a sphere, h = (x^2 + y^2) / 2,
approach 0.01 (a = 0.1), solved on one grid (&normal cells_across = 100,
target_error = 0: 50 cells across the contact's diameter), the pressure
written per cell. p0 is fitted on the cells within 0.7 a; each cell's
pressure is compared with Hertz's at its centre and with Hertz's mean over
the cell (20 x 20 points), binned by the centre's distance from the edge
in cells. The outermost cells hold about the cell's mean, not the centre
value; the cells behind them are within about 1 % of the centre value.

  /usr/bin/python3 lab/edge_pressure.py [--kcreep build/kcreep] [--cells 100]

Needs numpy; under a second.
"""
import argparse
import os
import subprocess
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--kcreep", default=os.path.join(ROOT, "build", "kcreep"))
    p.add_argument("--cells", type=int, default=100, help="&normal cells_across (default 100)")
    args = p.parse_args()
    import numpy as np

    a = 0.1   # Hertz's radius: sqrt(R approach), R = 1
    with tempfile.TemporaryDirectory() as work:
        with open(os.path.join(work, "sphere.nml"), "w") as f:
            f.write(f"&patch shape = 'gap' /\n&normal rx = 1.0, ry = 1.0, approach = 0.01, "
                    f"cells_across = {args.cells} /\n&material g = 1, nu = 0.25 /\n"
                    "&solver target_error = 0 /\n&output pressure_file = 'sphere.p' /\n")
        subprocess.run([args.kcreep, "sphere.nml"], cwd=work, check=True, capture_output=True)
        with open(os.path.join(work, "sphere.p")) as f:
            grid = [line.split() for line in f if line.startswith("# grid")][0]
        h = float(grid[-4])
        x, y, p_cell = np.loadtxt(os.path.join(work, "sphere.p"), usecols=(2, 3, 4), unpack=True)
    r = np.hypot(x, y)
    inner = r < 0.7 * a
    shape = 1 - (r / a) ** 2
    p0 = np.sum(p_cell[inner] * np.sqrt(shape[inner])) / np.sum(shape[inner])
    centre = p0 * np.sqrt(np.clip(shape, 0, None))
    s = (np.arange(20) + 0.5) / 20 - 0.5
    sx, sy = np.meshgrid(s, s)
    mean = np.array([np.mean(p0 * np.sqrt(np.clip(1 - ((xc + sx * h) ** 2 + (yc + sy * h) ** 2) / a**2, 0, None)))
                     for xc, yc in zip(x, y)])
    depth = (a - r) / h
    print(f"sphere, cells_across = {args.cells}: {2 * a / h:.0f} cells across the contact, p0 fitted {p0:.6g}")
    print("centre's distance inside the edge, cells | cells | p / Hertz at the centre | p / Hertz's cell mean")
    for lo, hi in ((-1, 0), (0, 0.5), (0.5, 1), (1, 1.5), (1.5, 2), (2, 3), (3, 5), (5, 10)):
        m = (depth >= lo) & (depth < hi)
        if not m.any():
            continue
        by_centre = f"{np.median(p_cell[m] / centre[m]):.3f}" if lo >= 0 else "-"
        print(f"{lo:5.1f} to {hi:4.1f} | {m.sum():5d} | {by_centre:>6s} | {np.median(p_cell[m] / mean[m]):.3f}")


if __name__ == "__main__":
    main()
