#!/usr/bin/env python3
"""Coefficients of the shipped masks with every cell split k x k (the same
patch on every level), for the refinement engine's calibration and the
references of docs/accuracy.md.

    lab/mask_split_levels.py [--max-cells N] [--splits 1,2,...] [--out FILE] [names...]

names: input/*.nml mask examples (default: all seven). Each level is solved
exactly as given (target_error 0, no estimate), iterative path, GMRES to a
relative residual of 1e-9; prints and appends 'name k n c11 c22 c23 seconds'.
"""
import os
import sys
import time

if any(a in ("-h", "--help") for a in sys.argv[1:]):
    print(__doc__.strip())
    sys.exit(0)
import numpy as np  # noqa: E402

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(REPO, "python"))
import kcreep  # noqa: E402

MASKS = {
    "kidney_inline": None, "two_patches": "two_patches.mask", "crescent": "crescent.mask",
    "two_lobed": "two_lobed.mask", "rectangle": "rectangle.mask", "superellipse": "superellipse.mask",
    "twin": "twin.mask",
}
KIDNEY = ["....######..", "..#########.", ".##########.", "#########...", "#######.....", "#######.....",
          "#########...", ".##########.", "..#########.", "....######.."]
MATERIAL = {"kidney_inline": (82000.0, 0.28), "two_patches": (1.0, 0.25)}


def load_mask(name):
    """(inside rows in increasing y, dx, dy, x0, y0, g, nu) of a shipped example."""
    g, nu = MATERIAL.get(name, (82000.0, 0.28))
    if name == "kidney_inline":
        rows = KIDNEY
        dx = dy = 0.5
        x0, y0 = -2.75, -2.25
    else:
        with open(os.path.join(REPO, "input", MASKS[name])) as f:
            lines = f.read().split("\n")
        mx, my, dx, dy, x0, y0 = lines[0].split()
        dx, dy, x0, y0 = float(dx), float(dy), float(x0), float(y0)
        rows = [l.strip() for l in lines[1:1 + int(my)]]
    inside = np.array([[c in "#1" for c in r] for r in rows])
    return inside, dx, dy, x0, y0, g, nu


def split(inside, dx, dy, x0, y0, k):
    fine = np.kron(inside, np.ones((k, k), dtype=bool))
    return fine, dx / k, dy / k, x0 - dx / 2 + dx / (2 * k), y0 - dy / 2 + dy / (2 * k)


def level(name, k, tolerance=1e-9):
    inside, dx, dy, x0, y0, g, nu = load_mask(name)
    s = kcreep.Solver(nu=nu, g=g, method="iterative", tolerance=tolerance, target_error=0.0,
                      refine_grid=False, estimate_error=False, threads=1)
    t = time.time()
    r = s.solve_mask(*split(inside, dx, dy, x0, y0, k))
    return int(inside.sum()) * k * k, r.c, time.time() - t


def main(args):
    max_cells, out, splits = 300000, None, None
    names = []
    i = 0
    while i < len(args):
        if args[i] == "--max-cells":
            max_cells = int(args[i + 1]); i += 2
        elif args[i] == "--out":
            out = args[i + 1]; i += 2
        elif args[i] == "--splits":
            splits = [int(s) for s in args[i + 1].split(",")]; i += 2
        else:
            names.append(args[i]); i += 1
    for name in names or list(MASKS):
        n1 = int(load_mask(name)[0].sum())
        for k in splits or range(1, 65):
            if n1 * k * k > max_cells:
                break
            n, c, sec = level(name, k)
            line = f"{name} {k} {n} {c[0]:.8f} {c[1]:.8f} {c[2]:.8f} {sec:.2f}"
            print(line, flush=True)
            if out:
                with open(out, "a") as f:
                    f.write(line + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
