#!/usr/bin/python3
"""The fast force model on larger patches (two levels above 350 solved cells):
build time (CPU, one thread) and distance from the exact forces at random
creepages, per patch.

    OMP_NUM_THREADS=1 /usr/bin/python3 lab/fast_model_levels.py [POINTS] [PATCH ...]
    OMP_NUM_THREADS=1 /usr/bin/python3 lab/fast_model_levels.py --s1002 [--default] [FORCE_CELLS] SHIFT ...

POINTS (default 1500) random creepages per patch, directions uniform in the
model's normalised creepage z = (f11 xi, f22 eta, f22 r phi) / (mu Fn), |z|
log-uniform 1e-5 to 30, mu = 0.3, seed 48 + the patch's index. The 'direct'
column of docs/rolling.md was measured with this script on a library built
with kcreep_fast_build's direct_build_cells raised to 100000.

--s1002: the rows of an S1002 / UIC60 kcreep.ContactTable at the given
shifts (mm; 70 kN, target 1e-2, cell budget 1000; FORCE_CELLS, default 0,
its force_cells): per row the fast model's build and its distance from the
exact forces on the same grid at 200 random creepages (normal, scales 1e-3,
1e-3, 3e-4 1/mm; mu = 0.3, seed 1), and with FORCE_CELLS > 0 the exact
forces' distance from those of the row's own grid. --default: the table at
the program's default target and cell budget, and 300 creepages per row
drawn as for the patches above (the first patch's z).
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


def s1002(args):
    default = "--default" in args
    args = [a for a in args if a != "--default"]
    force_cells = int(args[0]) if args and "." not in args[0] else 0
    shifts = [float(a) for a in (args[1:] if force_cells else args)]
    profiles = os.path.join(HERE, "..", "..", "shared", "profiles")
    files = os.path.join(profiles, "MBench_S1002_v3.prw"), os.path.join(profiles, "MBench_UIC60_v3.prr")
    options = dict(g=82000.0, nu=0.28, vertical_force=70e3, threads=1)
    if not default:
        options.update(target_error=1e-2, cell_budget=1000.0)
    table = kcreep.ContactTable(*files, shifts, force_cells=force_cells, **options)
    full = kcreep.ContactTable(*files, shifts, force_cells=0, **options) if force_cells else table
    mu = 0.3
    creep = np.random.default_rng(1).normal(size=(200, 3)) * [1e-3, 1e-3, 3e-4]
    for shift in shifts:
        if default:   # creepages as in main(): directions uniform in the row's z, |z| log-uniform
            f, patch = table.matrix(table._terms(shift)[0][0][0]), table.at(shift)[0]
            k = np.array([f[0, 0], f[1, 1], f[1, 1] * np.sqrt(patch["area"] / np.pi)]) / patch["fn"]
            rng = np.random.default_rng(1)
            z = rng.normal(size=(300, 3))
            z /= np.linalg.norm(z, axis=1)[:, None]
            creep = mu * z * (10 ** rng.uniform(-5, np.log10(30), 300))[:, None] / k
        t0 = time.process_time()
        table.forces(shift, mu, creep[:1])
        build = time.process_time() - t0
        fast, exact = table.forces(shift, mu, creep), table.forces(shift, mu, creep, exact=True)
        own = full.forces(shift, mu, creep, exact=True)
        for k, patch in enumerate(table.at(shift)):
            row = table._terms(shift)[k][0][0]
            e = np.hypot(*(fast[k] - exact[k])[:, :2].T) / (mu * patch["fn"])
            line = (f"shift {shift:g} mm, patch {k + 1} ({patch['kind']}, {table.solver(row)._result(False).n} cells): "
                    f"build {build:.2f} s, fast against exact: 95th percentile {100 * np.percentile(e, 95):.2f} %, "
                    f"largest {100 * e.max():.2f} %")
            if force_cells:
                g = np.hypot(*(exact[k] - own[k])[:, :2].T) / (mu * patch["fn"])
                line += f"; exact against the row's own grid: 95th {100 * np.percentile(g, 95):.2f} %, largest " \
                        f"{100 * g.max():.2f} %"
            print(line, flush=True)


if __name__ == "__main__":
    if sys.argv[1:2] == ["--s1002"]:
        s1002(sys.argv[2:])
    else:
        main()
