#!/usr/bin/python3
"""Do cells that blend the contact edge's two conditions make a ladder's
levels smoother than kcreep's staircases? (docs/wheel_rail.md, "Speed")

Steady rolling in full adhesion with the backward scheme, solved densely in
numpy (the model of cut_cell_study.py), on a unit circle and on an ellipse
a/b = 3 (its long edges along the grid's rows, as a flange strip's), each
level's grid moved by a random fraction of a cell. Two ways to turn a grid
into unknowns:

- staircase referred: the cells whose centres lie in the shape, f referred
  to the shape by the staircase's second moments (what kcreep does);
- blended edge: every cell the shape reaches is an unknown with its inside
  fraction phi (16 x 16 sample points); its equation is
      phi (slip + creepage) + (1 - phi) kappa d t = 0,
  d the slip's own-cell coefficient: no slip inside (phi = 1), no traction
  outside (phi = 0), continuous in between, so that a level's f moves
  continuously when the edge crosses a cell. f = the sum of t over the
  cells. kappa = 1, 2, 4 on the circle, 2 on the ellipse.

Prints per series the straight line f0 + K h through the levels, the
levels' rms scatter about it and f0 against the refined table; writes
lab/data/boundary_blend_study.dat and lab/figures/boundary_blend_study.png.

  /usr/bin/python3 lab/boundary_blend_study.py [--kcreep build/kcreep] [--no-write]

Needs numpy and matplotlib (Debian's python3-numpy, python3-matplotlib) and a
built kcreep (the refined table's values); about 6 minutes on one core.
"""
import argparse
import math
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SEED = 1
SAMPLES = 16
# (semi-axis a with b = 1, cells across the shorter axis: first, last, step, kappas)
CASES = ((1.0, (24, 64, 4), (1.0, 2.0, 4.0)), (3.0, (16, 40, 4), (2.0,)))


def arguments():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--kcreep", default=os.path.join(ROOT, "build", "kcreep"))
    p.add_argument("--no-write", action="store_true", help="print only; leave docs/ alone")
    return p.parse_args()


def solve_f(np, a, phi, kappa):
    """f11, f22 with each cell's equation blended by its inside fraction phi."""
    n = len(phi)
    w = np.r_[phi, phi]
    rhs = np.zeros((2 * n, 2))
    rhs[:n, 0] = 1
    rhs[n:, 1] = 1
    t = np.linalg.solve(w[:, None] * a + np.diag((1 - w) * kappa * np.diag(a)), w[:, None] * rhs)
    return -np.array([t[:n, 0].sum(), t[n:, 1].sum()])


def level(np, study, semi_a, cells, offset, kappas, slopes):
    """One level: C11, C22 of the referred staircase and of the blended edge per kappa."""
    h = 2.0 / cells
    mx, my = int(math.ceil(2.2 * semi_a / h)) + 2, int(math.ceil(2.2 / h)) + 2
    gx, gy = np.meshgrid(-1.1 * semi_a + (offset[0] + np.arange(mx)) * h, -1.1 + (offset[1] + np.arange(my)) * h,
                         indexing="ij")
    x, y = gx.ravel(), gy.ravel()
    s = ((np.arange(SAMPLES) + 0.5) / SAMPLES - 0.5) * h
    sx = x[:, None, None] + s[None, :, None] + 0 * s[None, None, :]
    sy = y[:, None, None] + 0 * s[None, :, None] + s[None, None, :]
    phi = ((sx / semi_a)**2 + sy**2 <= 1).mean((1, 2))
    centre = (x / semi_a)**2 + y**2 <= 1
    keep = (phi > 0) | centre
    x, y, phi, centre = x[keep], y[keep], phi[keep], centre[keep]
    squares = [(np.array([cx]), np.array([cy]), h / 2) for cx, cy in zip(x, y)]
    a = study.backward_operator(np, np.c_[x, y], squares, h)
    stair_rows = np.r_[centre, centre]
    stair = solve_f(np, a[np.ix_(stair_rows, stair_rows)], np.ones(centre.sum()), 0.0) * h * h
    # kcreep_staircase_normalisation referred_f: size and aspect ratio from the second moments
    a_s, b_s = (2 * math.sqrt(((c - c.mean())**2).mean() + h * h / 12) for c in (x[centre], y[centre]))
    row = list(stair / (a_s * b_s) * np.exp(-np.array(slopes) * math.log(a_s / b_s / semi_a)))
    for kappa in kappas:
        row += list(solve_f(np, a, phi, kappa) * h * h / semi_a)
    return row


def main(args):
    import numpy as np
    sys.path[:0] = [os.path.join(os.path.dirname(os.path.abspath(__file__)), d) for d in (".", "../tools/maintenance", "../scripts/convergence", "../tests/calibration")]
    import cut_cell_study as study
    study.NU = 0.25
    rng = np.random.default_rng(SEED)
    results = []
    for semi_a, (first, last, step), kappas in CASES:
        table = np.array(study.table_c(args.kcreep, semi_a))
        slopes = [math.log(hi / lo) / math.log(1.05**2)
                  for hi, lo in zip(study.table_c(args.kcreep, semi_a * 1.05), study.table_c(args.kcreep, semi_a / 1.05))]
        names = ["staircase referred"] + [f"blended edge, kappa {k:g}" for k in kappas]
        rows = []
        for cells in range(first, last + 1, step):
            c = level(np, study, semi_a, cells, rng.random(2), kappas, slopes)
            rows.append([cells] + [100 * (v / table[i % 2] - 1) for i, v in enumerate(c)])
            print(f"a/b {semi_a:g}, {cells:3d} cells across: error % " +
                  "  ".join(f"{rows[-1][1 + 2 * s]:+.4f} {rows[-1][2 + 2 * s]:+.4f}" for s in range(len(names))),
                  flush=True)
        data = np.array(rows)
        h = 2.0 / data[:, 0]
        print(f"\na/b = {semi_a:g}: refined table C11 {table[0]:.5f} C22 {table[1]:.5f}")
        print("| series | C | f0 - table | K (per 1/cells) | rms scatter about f0 + K h |")
        print("|---|---|---|---|---|")
        for s, name in enumerate(names):
            for c in range(2):
                e = data[:, 1 + 2 * s + c]
                design = np.c_[np.ones_like(h), h]
                coef = np.linalg.lstsq(design, e, rcond=None)[0]
                scatter = math.sqrt(np.mean((e - design @ coef)**2))
                print(f"| {name} | C{11 * (c + 1)} | {coef[0]:+.4f} % | {2 * coef[1]:+.1f} % | {scatter:.4f} % |")
        print()
        results.append((semi_a, names, data))
    if args.no_write:
        return
    with open(os.path.join(ROOT, "lab", "data", "boundary_blend_study.dat"), "w") as f:
        f.write("# lab/boundary_blend_study.py: nu = 0.25, backward scheme, random grid offsets\n")
        f.write("# per shape: cells_across, then C11 C22 error % against the refined table per series\n")
        for semi_a, names, data in results:
            f.write(f"# a/b = {semi_a:g}: " + "; ".join(names) + "\n")
            for row in data:
                f.write(f"{int(row[0]):d} " + " ".join(f"{v:+.5f}" for v in row[1:]) + "\n")
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
    for ax, (semi_a, names, data) in zip(axes, results):
        colours = {"staircase referred": "C0", "blended edge, kappa 1": "C1", "blended edge, kappa 2": "C2",
                   "blended edge, kappa 4": "C3"}
        for s, name in enumerate(names):
            ax.plot(1.0 / data[:, 0], data[:, 1 + 2 * s], "o-" if s else "s:", ms=3.5, color=colours[name],
                    label=f"C11, {name}")
        ax.axhline(0, color="k", lw=0.8)
        ax.set_xlabel("1 / cells across the shorter axis")
        ax.set_ylabel("error against the refined table, %")
        ax.set_title(f"ellipse a/b = {semi_a:g}" if semi_a != 1 else "circle")
        ax.legend(fontsize=7)
    fig.tight_layout()
    path = os.path.join(ROOT, "lab", "figures", "boundary_blend_study.png")
    fig.savefig(path, dpi=110)
    print("wrote", path)


if __name__ == "__main__":
    main(arguments())
