#!/usr/bin/python3
"""The fast force model on larger patches (two levels above 350 solved cells):
build time (CPU, one thread) and distance from the exact forces at random
creepages, per patch.

    OMP_NUM_THREADS=1 /usr/bin/python3 lab/fast_model_levels.py [POINTS] [PATCH ...]

POINTS (default 1500) random creepages per patch, directions uniform in the
model's normalised creepage z = (f11 xi, f22 eta, f22 r phi) / (mu Fn), |z|
log-uniform 1e-5 to 30, mu = 0.3, seed 48 + the patch's index. The 'direct'
column of docs/rolling.md was measured with this script on a library built
with kcreep_fast_build's fast_model_cell_cap raised to 100000.
"""
import os
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "python"))
sys.path.insert(0, os.path.join(HERE, "..", "scripts"))
import numpy as np  # noqa: E402
import kcreep  # noqa: E402
from bench_loop import ellipse, l_shape  # noqa: E402  (the benchmark's patches)


def crescent(m):
    x = (np.arange(m) + 0.5) / m * 2 - 1
    X, Y = np.meshgrid(x, x)
    d, x0, y0 = 2.0 / m, x[0], x[0]
    inside = (X ** 2 + Y ** 2 < 0.95) & ((X - 0.45) ** 2 + Y ** 2 > 0.45)
    return inside, np.clip(0.95 - X ** 2 - Y ** 2, 0, None) * np.clip((X - 0.45) ** 2 + Y ** 2 - 0.45, 0, None), \
        d, x0, y0


PATCHES = {"circle-36": lambda: ellipse(np, 1, 1, 36), "ab5-90": lambda: ellipse(np, 1, .2, 90),
           "ab0.2-18": lambda: ellipse(np, .2, 1, 18), "L-36": lambda: l_shape(np, 36),
           "crescent-40": lambda: crescent(40), "L-30": lambda: l_shape(np, 30),
           "circle-24": lambda: ellipse(np, 1, 1, 24), "ab2-40": lambda: ellipse(np, 1, .5, 40)}


def main():
    points = int(sys.argv[1]) if len(sys.argv) > 1 else 1500
    names = sys.argv[2:] or list(PATCHES)
    mu = 0.3
    for index, name in enumerate(PATCHES):
        if name not in names:
            continue
        inside, p, d, x0, y0 = PATCHES[name]()
        p = np.where(inside, p, 0.0)
        p /= p.sum() * d * d
        s = kcreep.Solver(threads=1, refine_grid=False, estimate_error=False, target_error=0)
        r = s.solve_mask(inside, d, d, x0, y0)
        radius = np.sqrt(inside.sum() * d * d / np.pi)
        # the rolling solver's own f11, f22 (a creepage of 1e-9)
        f11, f22 = [-s.rolling(1.0, [np.eye(3)[j] * 1e-9], p)[0][0, j] / 1e-9 for j in (0, 1)]
        k = np.array([f11, f22, f22 * radius])
        rng = np.random.default_rng(48 + index)
        z = rng.normal(size=(points, 3))
        z /= np.linalg.norm(z, axis=1)[:, None]
        z *= 10 ** rng.uniform(-5, np.log10(30), points)[:, None]
        creep = mu * z / k
        t0 = time.process_time()
        s.fast_forces(mu, creep[:1], p)
        build = time.process_time() - t0
        fast = s.fast_forces(mu, creep, p)
        exact = s.rolling(mu, creep, p)[0]
        e = np.hypot(*(fast - exact)[:, :2].T) / mu
        print(f"{name}: {r.n} cells, build {build:.2f} s, |F_fast - F_exact| / (mu Fn): 95th percentile "
              f"{100 * np.percentile(e, 95):.3f} %, largest {100 * e.max():.3f} %", flush=True)


if __name__ == "__main__":
    main()
