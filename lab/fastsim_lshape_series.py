#!/usr/bin/env python3
"""FASTSIM's default rule against plain FASTSIM on L-shaped patches, on the creepage series of
CONTACT's runs with friction (../shared/contact-slip/README.md: 24 cases, pure xi, eta, spin and
five combined, scaled per component by mu Fn / f11, mu Fn / f22, mu Fn / |f23| of the patch
relative to the 5 mm circle's), judged against the exact rolling solver (issue 48's 3 % criterion).

  /usr/bin/python3 lab/fastsim_lshape_series.py

L shapes (arms a1 x b1 along x and a2 x b2 along y, cells of 0.25 mm, the parabolic strip
pressure of a bare mask, nu = 0.25, G = 82000, mu = 0.3) in four orientations (mirrored in x and
in y), spun about the corner of the arms or about the centroid: 40 patches, 960 points. Prints
per patch the largest error of each rule and the largest excess of the default ('aligned') over
'separate' and over 'weighted', in % of mu Fn. About a minute of one CPU.
"""
import csv
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path[:0] = [os.path.join(ROOT, 'python'), os.path.join(ROOT, 'tests')]
import numpy as np  # noqa: E402
import kcreep  # noqa: E402
import kctest as kc  # noqa: E402

MU, G, NU, FN_CIRCLE = 0.3, 82000.0, 0.25, 82000.0
SHAPES = ((8, 2.5, 2.5, 7), (7, 2.5, 2.5, 8), (6, 3, 3, 6), (8, 2, 2, 8), (10, 3, 3, 5))
RULES = ('aligned', 'separate', 'weighted')


def series():
    """The 24 creepages (xi, eta, phi) of the circle's runs in ../shared/contact-slip/slip_summary.csv."""
    path = os.path.join(ROOT, '..', 'shared', 'contact-slip', 'slip_summary.csv')
    rows = [r for r in csv.DictReader(open(path)) if r['patch'] == 'circle']
    return np.array([[float(r[k]) for k in ('xi', 'eta', 'phi')] for r in sorted(rows, key=lambda r: int(r['case']))])


def lshape(h, a1, b1, a2, b2):
    m = np.arange(-1, int(max(a1, a2, b1, b2) / h) + 3)
    x, y = np.meshgrid(m * h + h / 2, m * h + h / 2)
    inside = ((x >= 0) & (x <= a1) & (y >= 0) & (y <= b1)) | ((x >= 0) & (x <= a2) & (y >= 0) & (y <= b2))
    return inside, x[0, 0], y[0, 0]


def main():
    h = 0.25
    circle = kcreep.Solver(nu=NU, g=G, target_error=0).solve_ellipse(5.0, 5.0, 44, 44)
    per_circle = FN_CIRCLE / np.array([circle.f[0, 0], circle.f[1, 1], abs(circle.f[1, 2])])
    worst = {'separate': (0, ''), 'weighted': (0, '')}
    above = {'separate': 0, 'weighted': 0}
    for dims in SHAPES:
        for flip_x in (False, True):
            for flip_y in (False, True):
                inside, x0, y0 = lshape(h, *dims)
                inside = inside[::-1 if flip_y else 1, ::-1 if flip_x else 1]
                x, y = np.meshgrid(x0 + h * np.arange(inside.shape[1]), y0 + h * np.arange(inside.shape[0]))
                for centre, (xs, ys) in (('corner', (x0, y0)), ('centroid', (x0 - x[inside].mean(), y0 - y[inside].mean()))):
                    s = kcreep.Solver(nu=NU, g=G, target_error=0)
                    r = s.solve_mask(inside, h, h, xs, ys)
                    pn = kc.parabolic(np, inside, h, h) * FN_CIRCLE
                    fn = pn.sum() * h * h
                    creep = series() * (fn / np.array([r.f[0, 0], r.f[1, 1], abs(r.f[1, 2])])) / per_circle
                    exact, _ = s.rolling(MU, creep, pn)
                    err = {}
                    for rule in RULES:
                        f, _ = s.fastsim(MU, creep, pn, rule)
                        err[rule] = np.hypot(*(f[:, :2] - exact[:, :2]).T) / (MU * fn)
                    name = f'{dims} mirrored x {flip_x:d} y {flip_y:d}, spun about the {centre}'
                    line = f'{name:50s} largest error ' + ' '.join(f'{k} {100 * v.max():4.1f}' for k, v in err.items())
                    for plain in worst:
                        excess = err['aligned'] - err[plain]
                        k = int(excess.argmax())
                        above[plain] += int((excess > 0.03).sum())
                        worst[plain] = max(worst[plain], (excess[k], f'{name}, case {k + 1}'))
                        line += f' | over {plain} {100 * excess[k]:4.2f} (case {k + 1})'
                    print(line, flush=True)
    for plain, (value, where) in worst.items():
        print(f'excess over {plain}: largest {100 * value:.2f} % of mu Fn ({where}); above 3 % at {above[plain]} of 960 points')


if __name__ == '__main__':
    main()
