#!/usr/bin/env python3
"""FASTSIM's default rule ('aligned') against plain FASTSIM with the same L, point by point, at
random creepages, on the 110 patches of scripts/fastsim_vs_exact.py (issue 48).

  /usr/bin/python3 lab/fastsim_plain_excess.py [--random N] [--seed S] [NAME ...]

Each patch through the Python API (Solver.solve_ellipse / solve_mask / solve_gap on the study's
grid, target_error = 0; pressure: Hertz on the ellipses, the parabolic strip model on the masks,
the normal solve's on the gaps), then Solver.rolling (exact) and Solver.fastsim with the rules
'aligned', 'separate' and 'weighted' at the same creepages: pure xi, eta, +phi, -phi at 9 levels
s = 0.02 .. 10 and N random directions (uniform on the sphere of the normalised creepage
(f11 xi, f22 eta, f22 c phi) / (mu Fn), c = sqrt(area/pi)) with s log-uniform in 0.01 .. 10, mu =
0.3. Error of a point |F - F_exact| / (mu Fn), F = (Fx, Fy); excess = error of 'aligned' less that
of a plain rule. Prints per patch the largest error of each rule, the largest excess over
'separate' and over 'weighted', and a summary. NAME: only patches whose name contains it.
KCREEP_LIBRARY picks another build's libkcreep.so (a before/after comparison at the same points).
About 3 minutes of one CPU; runs under /tmp/kcreep-bench.lock if called through flock."""
import argparse
import math
import os
import random
import re
import sys

HERE = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(HERE, 'tests'))
import kctest  # noqa: E402  (the tests' mask pressure, parabolic)
MU = 0.3
LEVELS = (0.02, 0.1, 0.3, 0.6, 1.0, 1.5, 2.5, 4.0, 10.0)
RULES = ('aligned', 'separate', 'weighted')


def study():
    import importlib.util
    spec = importlib.util.spec_from_file_location('fastsim_vs_exact', os.path.join(HERE, 'scripts', 'fastsim_vs_exact.py'))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def grid_of(np, text, numeric):
    lines = [w for w in text.strip('\n').split('\n') if not w.startswith('%')]
    mx, my, dx, dy, x0, y0 = lines[0].split()
    rows = lines[1:1 + int(my)]
    a = np.array([[float(v) for v in r.split()] for r in rows]) if numeric else np.array([[c == '#' for c in r] for r in rows])
    return a, float(dx), float(dy), float(x0), float(y0)


def setup(np, kcreep, patch):
    """(solver, pressure or None, Fn, c, result) of a study patch."""
    family, name, desc, head, files, pressure = patch
    number = lambda key: float(re.search(key + r' = ([0-9.e+-]+)', head).group(1))  # noqa: E731
    if family == 'ellipse':
        a, b = number('semi_a'), number('semi_b')
        mx, my = int(number('mx')), int(number('my'))
        s = kcreep.Solver(nu=number('nu'), g=1.0, target_error=0)
        r = s.solve_ellipse(a, b, mx, my)
        dx, dy = 2 * a / mx, 2 * b / my
        x, y = np.meshgrid(-a + dx * (np.arange(mx) + 0.5), -b + dy * (np.arange(my) + 0.5))
        pn = np.sqrt(np.maximum(0, 1 - (x / a) ** 2 - (y / b) ** 2))
        return s, pn / (pn.sum() * dx * dy), 1.0, math.sqrt(a * b), r
    if family == 'mask':
        inside, dx, dy, x0, y0 = grid_of(np, list(files.values())[0], False)
        s = kcreep.Solver(nu=number('nu'), g=1.0, target_error=0)
        r = s.solve_mask(inside, dx, dy, x0, y0)
        return s, kctest.parabolic(np, inside, dx, dy), 1.0, math.sqrt(inside.sum() * dx * dy / math.pi), r
    if files:
        gap, dx, dy, x0, y0 = grid_of(np, list(files.values())[0], True)
        s = kcreep.Solver(nu=number('nu'), g=82000.0, target_error=0)
    else:
        gap, dx, dy, x0, y0 = grid_of(np, open(os.path.join(HERE, 'input', 'wheel_rail.gap')).read(), True)
        s = kcreep.Solver(bodies=(210000.0, 0.28, 210000.0, 0.28), target_error=0)
    r = s.solve_gap(gap, dx, dy, x0, y0, approach=number('approach'))
    return s, None, r.fn, math.sqrt(r.n * dx * dy / math.pi), r


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0], epilog=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('--random', type=int, default=150, help='random creepages per patch (default 150)')
    ap.add_argument('--seed', type=int, default=48)
    ap.add_argument('names', nargs='*')
    args = ap.parse_args()
    sys.path.insert(0, os.path.join(HERE, 'python'))
    import numpy as np
    import kcreep
    rng = np.random.default_rng(args.seed)
    excess = {'separate': [], 'weighted': []}
    errs = {r: [] for r in RULES}
    for patch in study().generate_patches(random.Random(30)):
        if args.names and not any(n in patch[1] for n in args.names):
            continue
        s, pn, fn, c, r = setup(np, kcreep, patch)
        dirs = [(d, lv) for d in ((1, 0, 0), (0, 1, 0), (0, 0, 1), (0, 0, -1)) for lv in LEVELS]
        for _ in range(args.random):
            v = rng.normal(size=3)
            dirs.append((v / np.linalg.norm(v), 10 ** rng.uniform(-2, 1)))
        scale = (r.f[0, 0], r.f[1, 1], r.f[1, 1] * c)
        creep = np.array([[d[k] * lv * MU * fn / scale[k] for k in range(3)] for d, lv in dirs])
        exact, _ = s.rolling(MU, creep, pn)
        e = {}
        for rule in RULES:
            f, _ = s.fastsim(MU, creep, pn, rule)
            e[rule] = np.hypot(*(f[:, :2] - exact[:, :2]).T) / (MU * fn)
            errs[rule].append(e[rule])
        line = f'{patch[1]:14s} L3 {r.fastsim[2]:7.3f}  largest error: ' + ' '.join(
            f'{rule} {100 * e[rule].max():5.1f}' for rule in RULES) + '  | largest excess over'
        for plain in excess:
            x = e['aligned'] - e[plain]
            excess[plain].append((x.max(), patch[1], (x > 0.03).sum(), len(x)))
            line += f' {plain} {100 * x.max():5.1f}'
        print(line + ' % of mu Fn', flush=True)
    print()
    for rule in RULES:
        v = np.concatenate(errs[rule])
        print(f'{rule:9s} error over {v.size} points: median {100 * np.median(v):.2f}, 95th percentile '
              f'{100 * np.percentile(v, 95):.2f}, mean {100 * v.mean():.2f}, largest {100 * v.max():.1f} % of mu Fn')
    for plain, rows in excess.items():
        worst = max(rows)
        print(f'excess over {plain}: largest {100 * worst[0]:.1f} % ({worst[1]}); above 3 % on '
              f'{sum(r[0] > 0.03 for r in rows)} of {len(rows)} patches, {sum(r[2] for r in rows)} of '
              f'{sum(r[3] for r in rows)} points')


if __name__ == '__main__':
    main()
