#!/usr/bin/python3
"""Would cells cut by the contact edge make a ladder's levels smoother than
kcreep's staircases? (docs/wheel_rail.md, "Speed")

A unit circle (G = 1, nu = 0.25), steady rolling in full adhesion with the
backward scheme (kcreep_assembly: (u(x + dx) - u(x)) / dx = creepage at the
collocation points), solved densely here in numpy on grids of N = 16 to 48
cells across, each grid moved by a random fraction of a cell in x and y (as
a contact area's levels fall on the area). Three ways to turn a grid into
unknowns:

- staircase: the cells whose centres lie in the circle, f as solved;
- staircase referred: the same f referred to the circle by the staircase's
  second moments (kcreep_staircase_normalisation: size and aspect ratio,
  the aspect slope of C11 and C22 from kcreep's refined table);
- cut cells: every cell the circle reaches, its traction on the part inside
  (the part's area and influence from sub x sub subcells), the slip taken
  at that part's centroid; a cell less than half inside is merged into its
  most-inside neighbour (a sliver's equation is nearly its neighbour's).

Prints per series the fit f0 + K h through the levels, the levels' rms
scatter about it and f0 against the circle's C11, C22 from the refined
table; writes lab/data/cut_cell_study.dat and lab/figures/cut_cell_study.png.

  /usr/bin/python3 lab/cut_cell_study.py [--kcreep build/kcreep] [--sub 8]

Needs numpy and matplotlib (Debian's python3-numpy, python3-matplotlib) and a
built kcreep (the refined table's values); about 4 minutes on one core.
"""
import argparse
import math
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
NU = 0.25
SEED = 1


def arguments():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--kcreep", default=os.path.join(ROOT, "build", "kcreep"))
    p.add_argument("--levels", default="16,48,2", help="first, last, step of the cells across the diameter")
    p.add_argument("--sub", type=int, default=8, help="subcells per cell side for the cut cells' parts")
    p.add_argument("--no-write", action="store_true", help="print only; leave docs/ alone")
    return p.parse_args()


def table_c(kcreep, a_over_b):
    """C11, C22 of the ellipse a/b (b = 1) from kcreep's refined table."""
    with tempfile.TemporaryDirectory() as work:
        path = os.path.join(work, "t.nml")
        with open(path, "w") as f:
            f.write(f"&patch shape = 'ellipse', semi_a = {a_over_b!r}, semi_b = 1.0 /\n&material g = 1, nu = {NU} /\n"
                    "&solver method = 'table' /\n&output table_file = '' /\n")
        out = subprocess.run([kcreep, path], cwd=work, capture_output=True, text=True, check=True).stdout
    values = {}
    for line in out.splitlines():
        words = line.split()
        if len(words) >= 3 and words[0] in ("C11", "C22") and words[1] == "=":
            values[words[0]] = float(words[2])
    return values["C11"], values["C22"]


def influence(np, xr, yr, a, b):
    """Displacement difference (u_xx, u_xy, u_yy) at (xr, yr) from unit traction on
    a cell of half sizes a, b centred at 0 (kcreep_influence cell_displacement)."""
    def x_asinh(x, y):
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(x == 0, 0.0, x * np.arcsinh(y / np.abs(x)))
    uxx = uxy = uyy = 0.0
    for i, x in enumerate((xr + a, xr - a)):
        for j, y in enumerate((yr + b, yr - b)):
            sign = 1.0 if i == j else -1.0
            xl, yl = x_asinh(x, y), x_asinh(y, x)
            uxx = uxx + sign * ((1 - NU) * xl + yl)
            uyy = uyy + sign * (xl + (1 - NU) * yl)
            uxy = uxy - sign * NU * np.hypot(x, y)
    return uxx / math.pi, uxy / math.pi, uyy / math.pi


def backward_operator(np, points, parts, dx):
    """The backward scheme's matrix: slip at points[k] (x then y rows) from
    traction (px then py) on parts[k] = (x, y, half size) of rectangles."""
    n = len(points)
    at = np.vstack([points + [dx, 0.0], points])
    a = np.zeros((2 * n, 2 * n))
    for k, (cx, cy, half) in enumerate(parts):
        uxx, uxy, uyy = (u.sum(1) for u in influence(np, at[:, :1] - cx, at[:, 1:] - cy, half, half))
        a[:n, k], a[n:, k] = (uxx[:n] - uxx[n:]) / dx, (uxy[:n] - uxy[n:]) / dx
        a[:n, n + k], a[n:, n + k] = (uxy[:n] - uxy[n:]) / dx, (uyy[:n] - uyy[n:]) / dx
    return a


def solve(np, points, parts, dx):
    """f11, f22 of unknowns with traction on parts[k], the slip taken at
    points[k] (backward_operator, unit xi, eta)."""
    n = len(points)
    a = backward_operator(np, points, parts, dx)
    rhs = np.zeros((2 * n, 2))
    rhs[:n, 0] = 1
    rhs[n:, 1] = 1
    return np.linalg.solve(a, rhs)


def staircase_level(np, x, y, h):
    """The cells with centres inside: f11, f22 and the staircase's semi-axes."""
    inside = x**2 + y**2 <= 1
    px, py = x[inside], y[inside]
    points = np.c_[px, py]
    parts = [(np.array([cx]), np.array([cy]), h / 2) for cx, cy in points]
    t = solve(np, points, parts, h)
    n = len(points)
    f = -h * h * np.array([t[:n, 0].sum(), t[n:, 1].sum()])
    semi = [2 * math.sqrt(((c - c.mean())**2).mean() + h * h / 12) for c in (px, py)]
    return f, semi


def cut_level(np, x, y, h, sub):
    """Every cell the circle reaches, traction on its inside part (slivers merged)."""
    offsets = ((np.arange(sub) + 0.5) / sub - 0.5) * h
    sx = x[:, None, None] + offsets[None, :, None] + 0 * offsets[None, None, :]
    sy = y[:, None, None] + 0 * offsets[None, :, None] + offsets[None, None, :]
    inside = sx**2 + sy**2 <= 1
    share = inside.mean((1, 2))
    index = {(round(cx / h * 2), round(cy / h * 2)): k for k, (cx, cy) in enumerate(zip(x, y)) if share[k] > 0}
    owner = {}
    for (ix, iy), k in index.items():
        if share[k] >= 0.5:
            owner[k] = k
            continue
        near = [index.get((ix + 2 * dx, iy + 2 * dy)) for dx in (-1, 0, 1) for dy in (-1, 0, 1) if dx or dy]
        near = [j for j in near if j is not None and share[j] >= 0.5]
        if near:
            owner[k] = max(near, key=lambda j: share[j])
    members = {}
    for k, o in owner.items():
        members.setdefault(o, []).append(k)
    points, parts, area = [], [], []
    for ks in members.values():
        px = np.concatenate([sx[k][inside[k]] for k in ks])
        py = np.concatenate([sy[k][inside[k]] for k in ks])
        points.append([px.mean(), py.mean()])
        parts.append((px, py, h / (2 * sub)))
        area.append(len(px) * (h / sub)**2)
    points, area = np.array(points), np.array(area)
    t = solve(np, points, parts, h)
    n = len(points)
    return -np.array([(t[:n, 0] * area).sum(), (t[n:, 1] * area).sum()])


def main(args):
    import numpy as np
    first, last, step = (int(v) for v in args.levels.split(","))
    c_circle = table_c(args.kcreep, 1.0)
    ratio = 1.05
    slopes = [math.log(hi / lo) / math.log(ratio**2) for hi, lo in zip(table_c(args.kcreep, ratio),
                                                                         table_c(args.kcreep, 1 / ratio))]
    rng = np.random.default_rng(SEED)
    rows = []
    for cells in range(first, last + 1, step):
        h = 2.0 / cells
        offset = rng.random(2)
        m = int(math.ceil(2.4 / h)) + 2
        gx, gy = np.meshgrid(-1.2 + (offset[0] + np.arange(m)) * h, -1.2 + (offset[1] + np.arange(m)) * h,
                             indexing="ij")
        x, y = gx.ravel(), gy.ravel()
        stair, (a_s, b_s) = staircase_level(np, x, y, h)
        # kcreep_staircase_normalisation referred_f for an ellipse reference a = b = 1
        referred = stair / (a_s * b_s) * np.exp(-np.array(slopes) * math.log(a_s / b_s))
        cut = cut_level(np, x, y, h, args.sub)
        rows.append((cells, *stair, *referred, *cut))
        print(f"{cells:3d} cells across: staircase {stair[0]:.5f} {stair[1]:.5f}  referred {referred[0]:.5f} "
              f"{referred[1]:.5f}  cut cells {cut[0]:.5f} {cut[1]:.5f}", flush=True)
    data = np.array(rows)
    h = 2.0 / data[:, 0]
    print(f"\nrefined table (continuum): C11 {c_circle[0]:.5f}  C22 {c_circle[1]:.5f}")
    print("| series | C | f0 of f0 + K h | f0 against the table | rms scatter about the line |")
    print("|---|---|---|---|---|")
    names = ("staircase", "staircase referred", "cut cells")
    for s, name in enumerate(names):
        for c in range(2):
            f = data[:, 1 + 2 * s + c]
            design = np.c_[np.ones_like(h), h]
            coef = np.linalg.lstsq(design, f, rcond=None)[0]
            scatter = np.sqrt(np.mean((f - design @ coef)**2)) / coef[0]
            print(f"| {name} | C{11 * (c + 1)} | {coef[0]:.5f} | {100 * (coef[0] / c_circle[c] - 1):+.3f} % | "
                  f"{100 * scatter:.3f} % |")
    if args.no_write:
        return
    with open(os.path.join(ROOT, "lab", "data", "cut_cell_study.dat"), "w") as f:
        f.write("# lab/cut_cell_study.py: the unit circle, nu = 0.25, backward scheme, random grid offsets\n")
        f.write(f"# refined table C11 {c_circle[0]:.6f} C22 {c_circle[1]:.6f}; subcells {args.sub} per side\n")
        f.write("# cells_across C11 C22 (staircase) C11 C22 (staircase referred) C11 C22 (cut cells)\n")
        for row in rows:
            f.write(f"{row[0]:d} " + " ".join(f"{v:.6f}" for v in row[1:]) + "\n")
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(10, 4))
    for c, ax in enumerate(axes):
        for s, (name, style) in enumerate(zip(names, ("o:", "s-", "^-"))):
            ax.plot(h, data[:, 1 + 2 * s + c], style, label=name, ms=4)
        ax.axhline(c_circle[c], color="k", lw=0.8, label="refined table")
        ax.set_xlabel("h (cell size / radius)")
        ax.set_ylabel(f"C{11 * (c + 1)}")
        ax.set_xlim(left=0)
    axes[0].legend(fontsize=8)
    fig.suptitle("Unit circle, levels on randomly placed grids: staircase, referred staircase, cut cells")
    fig.tight_layout()
    fig.savefig(os.path.join(ROOT, "lab", "figures", "cut_cell_study.png"), dpi=110)


if __name__ == "__main__":
    main(arguments())
