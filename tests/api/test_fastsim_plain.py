"""FASTSIM's default rule ('aligned') against plain FASTSIM with the same L (issue 48): on pure
creepages the default may not be worse than plain FASTSIM by more than 3 % of mu Fn at any point,
judged against the exact rolling solver (Solver.rolling): err_default - err_plain <= 0.03, err =
|F - F_exact| / (mu Fn), F = (Fx, Fy). Plain FASTSIM: the rules 'weighted' (Kalker's single L)
and 'separate' (L1, L2, L3 on their terms), which are the same on pure creepage (checked).

- Patches (masks, the parabolic strip pressure of a bare mask, nu = 0.28): an L shape (arms
  8 x 2.5 and 2.5 x 7, cells of 0.25) spun about three points: two where L3 = I3/f23 < 0 (f23 and
  the strip integral I3 differ in sign: f23 nearly cancels), one at its corner (L3 > 0); and
  make_shapes' crescent mirrored in x (horns toward -x, cells of 0.2), spun about three points,
  two with L3 < 0.
- Points: pure spin of both signs at 11 levels s = 0.02 .. 10 of the linear theory (f22 c phi =
  s mu Fn, c = sqrt(area/pi)), and on the crescents pure xi and eta at the same levels.
- Measured (this build): largest excess 0.47 and 0.61 % on the L shape with L3 < 0 (largest
  errors: default 8.7 and 48 %, plain 67 and 57 %), none on the crescents with L3 < 0 (the
  default better: 4.4 and 6.9 % against 27 %), 0 where L3 > 0. Before the aligned rule took |L3|
  on both spin terms (a negative L3 on one spin term and |L3| on the other): 13.8 and 19.4 % on
  the L shape, 13.2 and 12.0 % on the crescent.
- On patches with L3 > 0 the default and plain FASTSIM give the same forces on pure creepage
  (1e-12 of mu Fn).
Combined creepages are not held to the 3 % here: the default is the better rule on average
(docs/fastsim.md, "Against the exact solver") but loses to plain FASTSIM by more than 3 % at some combined points
of most patches (lab/notes/fastsim_trials.md).

usage: /usr/bin/python3 test_fastsim_plain.py KCREEP SOURCE_DIR   (needs numpy)
"""
import math
import os
import sys

import kctest as kc

kc.setup()
root = os.path.abspath(sys.argv[2])
sys.path.insert(0, os.path.join(root, "python"))
import numpy as np  # noqa: E402
import kcreep  # noqa: E402

MU = 0.3
LEVELS = np.array([0.02, 0.05, 0.1, 0.2, 0.3, 0.5, 0.8, 1.2, 2.0, 4.0, 10.0])


def lshape(h=0.25):
    m = np.arange(-1, 35)
    x, y = np.meshgrid(m * h + h / 2, m * h + h / 2)
    inside = ((x >= 0) & (x <= 8) & (y >= 0) & (y <= 2.5)) | ((x >= 0) & (x <= 2.5) & (y >= 0) & (y <= 7))
    return inside, h, x[0, 0], y[0, 0]


def crescent(h=0.2):
    """make_shapes.py's crescent mirrored in x: 8 <= |(x + 9, y)| <= 11, |y| <= 6.5, x > -9."""
    m = np.arange(-12, 24)
    n = np.arange(-36, 36)
    x, y = np.meshgrid(-(m * h + h / 2), n * h + h / 2)
    x, y = x[:, ::-1], y[:, ::-1]
    d = np.hypot(-x - 9.0, y)
    inside = (d >= 8.0) & (d <= 11.0) & (np.abs(y) <= 6.5) & (-x < 9.0)
    return inside, h, x[0, 0], y[0, 0]


def check(name, inside, h, x0, y0, directions, limit):
    s = kcreep.Solver(nu=0.28, g=1.0, target_error=0)
    r = s.solve_mask(inside, h, h, x0, y0)
    pn = kc.parabolic(np, inside, h, h)
    c = math.sqrt(inside.sum() * h * h / math.pi)
    scale = [r.f[0, 0], r.f[1, 1], r.f[1, 1] * c]
    creep = np.array([[d[k] * lv * MU / scale[k] for k in range(3)] for d in directions for lv in LEVELS])
    exact, _ = s.rolling(MU, creep, pn)
    force, err = {}, {}
    for rule in ("aligned", "separate", "weighted"):
        force[rule], _ = s.fastsim(MU, creep, pn, rule)
        err[rule] = np.hypot(*(force[rule][:, :2] - exact[:, :2]).T) / MU
    same = np.abs(force["weighted"] - force["separate"])[:, :2].max() / MU
    kc.check(same < 1e-12, f"{name}: the plain rules alike on pure creepage ({same:.1e} mu Fn)")
    excess = 100 * (err["aligned"] - err["separate"]).max()
    l3 = r.fastsim[2]
    print(f"{name}: L3 = {l3:.3f}, {len(creep)} pure points, default's largest excess over plain FASTSIM "
          f"{excess:.2f} % of mu Fn (largest errors: default {100 * err['aligned'].max():.1f} %, "
          f"plain {100 * err['separate'].max():.1f} %)")
    kc.check(excess <= limit, f"{name}: default at most {limit} % of mu Fn worse than plain FASTSIM ({excess:.2f} %)")
    if l3 > 0:
        d = np.abs(force["aligned"] - force["separate"])[:, :2].max() / MU
        kc.check(d < 1e-12, f"{name}: L3 > 0, default = plain FASTSIM on pure creepage ({d:.1e} mu Fn)")
    return l3


spin = [(0, 0, 1), (0, 0, -1)]
inside, h, x0, y0 = lshape()
for shift, sign in ((-4.9, -1), (-4.8, -1), (0.0, 1)):
    l3 = check(f"L shape, spin centre at x = {-shift} from its corner", inside, h, x0 + shift, y0 - 2.0, spin, 3.0)
    kc.check(np.sign(l3) == sign, f"L shape: L3 {l3:.3f} of the sign the check needs ({sign:+d})")
inside, h, x0, y0 = crescent()
pure = [(1, 0, 0), (-1, 0, 0), (0, 1, 0), (0, -1, 0)] + spin
for shift, sign in ((-0.05, -1), (-0.03, -1), (1.0, 1)):
    l3 = check(f"crescent, spin centre at x = {-shift}", inside, h, x0 + shift, y0, pure, 3.0)
    kc.check(np.sign(l3) == sign, f"crescent: L3 {l3:.3f} of the sign the check needs ({sign:+d})")
kc.finish()
