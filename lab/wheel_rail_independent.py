#!/usr/bin/env python3
"""An independent rigid contact-point search for a wheel on a rail (no kcreep
code): reads the two SIMPACK profiles itself, places them as &wheel_rail's
defaults describe (CONTACT's module 1: the gauge point, the innermost rail point
at most 14 mm below the rail top, at y = 1435/2; the wheel profile's origin at
1360/2 + 70 + shift; nominal radius 460), and for each lateral shift lowers the
wheel until it touches. Prints, per shift, the contact point on each profile,
the contact angle, the rolling radius, Hertz's patch (from the curvatures at the
contact point, normal force 80 kN / cos(delta), G = 82000, nu = 0.28) and, when a
kcreep table is given, kcreep's values beside them.

  lab/wheel_rail_independent.py [--wr TABLE.wr] [--profiles FOLDER]
      --profiles  the folder with MBench_S1002_v3.prw and MBench_UIC60_v3.prr
                  (default: ../shared/profiles beside the repository)
      --wr        kcreep's table of input/s1002_uic60.nml to compare with

Method (its own): natural cubic splines of y and z in the chord length of the
points, sampled every 0.005 mm; the wheel's lowest and the rail's highest point
per 0.005 mm of y; the minimum of the vertical clearance refined by a parabola;
the contact angle from the rail's spline slope; curvatures from the splines'
second derivatives. numpy only.
"""
import math
import os
import sys

if any(a in ("-h", "--help") for a in sys.argv[1:]):
    print(__doc__.strip())
    sys.exit(0)

import numpy as np  # noqa: E402

here = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
args = sys.argv[1:]
profiles = os.path.join(here, "..", "shared", "profiles")
wr = None
if "--profiles" in args:
    profiles = args[args.index("--profiles") + 1]
if "--wr" in args:
    wr = args[args.index("--wr") + 1]


def read_simpack(path):
    """The points (y, z) of a SIMPACK profile after the keys these files use:
    mirror.y, mirror.z, inversion, units.len.f (mm)."""
    keys, points, inside = {}, [], False
    for line in open(path):
        line = line.split("!")[0].strip()
        if not line:
            continue
        if line == "point.begin":
            inside = True
        elif line == "point.end":
            inside = False
        elif inside:
            points.append([float(v) for v in line.split()[:2]])
        elif "=" in line:
            k, v = line.split("=", 1)
            keys[k.strip()] = v.strip().strip("'")
    p = np.array(points) * (1000.0 / float(keys.get("units.len.f", 1000)))
    for k in ("shift.y", "shift.z", "rotate", "point.dist.min"):
        assert float(keys.get(k, 0)) == 0, f"{path}: {k} not handled by this script"
    if int(keys.get("mirror.y", 0)):
        p[:, 0] = -p[:, 0]
    if int(keys.get("mirror.z", 0)):
        p[:, 1] = -p[:, 1]
    if int(keys.get("inversion", 0)):
        p = p[::-1]
    return p


def spline(s, f):
    """Natural cubic spline through (s, f): returns its second derivatives."""
    n = len(s)
    h = np.diff(s)
    a = np.zeros((n, n))
    r = np.zeros(n)
    a[0, 0] = a[-1, -1] = 1
    for i in range(1, n - 1):
        a[i, i - 1], a[i, i], a[i, i + 1] = h[i - 1], 2 * (h[i - 1] + h[i]), h[i]
        r[i] = 6 * ((f[i + 1] - f[i]) / h[i] - (f[i] - f[i - 1]) / h[i - 1])
    return np.linalg.solve(a, r)


def evaluate(s, f, m, t):
    """The spline, its first and second derivative at t."""
    i = np.clip(np.searchsorted(s, t) - 1, 0, len(s) - 2)
    h = s[i + 1] - s[i]
    u, v = (s[i + 1] - t) / h, (t - s[i]) / h
    val = m[i] * u ** 3 * h * h / 6 + m[i + 1] * v ** 3 * h * h / 6 + (f[i] - m[i] * h * h / 6) * u + \
        (f[i + 1] - m[i + 1] * h * h / 6) * v
    d1 = -m[i] * u * u * h / 2 + m[i + 1] * v * v * h / 2 + (f[i + 1] - f[i]) / h - (m[i + 1] - m[i]) * h / 6
    d2 = m[i] * u + m[i + 1] * v
    return val, d1, d2


class Profile:
    def __init__(self, p):
        self.s = np.concatenate([[0], np.cumsum(np.hypot(*np.diff(p, axis=0).T))])
        self.y, self.z = p[:, 0], p[:, 1]
        self.my, self.mz = spline(self.s, self.y), spline(self.s, self.z)
        t = np.arange(0, self.s[-1], 0.005)
        self.ty = evaluate(self.s, self.y, self.my, t)[0]
        self.tz = evaluate(self.s, self.z, self.mz, t)[0]
        self.t = t

    def envelope(self, grid, lowest):
        """z per y of grid: the largest z (a wheel's lowest point) or the smallest (a rail's top)."""
        k = np.clip(np.round((self.ty - grid[0]) / (grid[1] - grid[0])).astype(int), 0, len(grid) - 1)
        out = np.full(len(grid), -np.inf if lowest else np.inf)
        (np.maximum if lowest else np.minimum).at(out, k, self.tz)
        out[(grid < self.ty.min()) | (grid > self.ty.max())] = np.nan
        return out

    def at_y(self, y, lowest):
        """z, dz/dy, d2z/dy2 of the branch through y (the lowest or highest one)."""
        best = None
        for j in range(len(self.t) - 1):
            pass
        cand = np.where((self.ty[:-1] - y) * (self.ty[1:] - y) <= 0)[0]
        vals = []
        for j in cand:
            lo, hi = self.t[j], self.t[j + 1]
            for _ in range(60):                      # bisection in the chord length
                mid = (lo + hi) / 2
                if (evaluate(self.s, self.y, self.my, lo)[0] - y) * (evaluate(self.s, self.y, self.my, mid)[0] - y) <= 0:
                    hi = mid
                else:
                    lo = mid
            yv, y1, y2 = evaluate(self.s, self.y, self.my, lo)
            zv, z1, z2 = evaluate(self.s, self.z, self.mz, lo)
            dz = z1 / y1
            d2z = (z2 * y1 - z1 * y2) / y1 ** 3
            vals.append((zv, dz, d2z))
        best = max(vals) if lowest else min(vals)
        return best


def hertz(a_curv, b_curv, force, g, nu):
    """Hertz's semi-axes along x and y for h = A x^2 + B y^2."""
    A, B = a_curv, b_curv
    big, small = max(A, B), min(A, B)

    def ke(e2):
        a, b, total, p = 1.0, math.sqrt(1 - e2), e2 / 2, 1.0
        while True:
            cn = (a - b) / 2
            a, b = (a + b) / 2, math.sqrt(a * b)
            total += p * cn * cn
            p *= 2
            if cn < 1e-16:
                break
        K = math.pi / (2 * a)
        return K, K * (1 - total)
    lo, hi = 1e-12, 1 - 1e-12
    for _ in range(200):
        e2 = (lo + hi) / 2
        K, E = ke(e2)
        ratio = (E / (1 - e2) - K) / (K - E)
        lo, hi = (e2, hi) if ratio < big / small else (lo, e2)
    K, E = ke(e2)
    semi_long = (3 * force * (1 - nu) / g * (K - E) / (2 * math.pi * e2 * small)) ** (1 / 3)
    semi_short = semi_long * math.sqrt(1 - e2)
    return (semi_long, semi_short) if A <= B else (semi_short, semi_long)


wheel = Profile(read_simpack(os.path.join(profiles, "MBench_S1002_v3.prw")))
rail = Profile(read_simpack(os.path.join(profiles, "MBench_UIC60_v3.prr")))
# the rail: top at z = 0, gauge point (innermost within 14 mm below the top) at y = 717.5
rail_dz = -rail.tz.min()
band = rail.tz + rail_dz <= 14
rail_dy = 1435 / 2 - rail.ty[band].min()
origin, r_nom = 1360 / 2 + 70, 460.0
step = 0.005
grid = np.arange(rail.ty.min() + rail_dy, rail.ty.max() + rail_dy, step)
z_rail = rail.envelope(grid - rail_dy, False) + rail_dz

kcreep_rows = {}
if wr:
    names = None
    for line in open(wr):
        if line.startswith("#"):
            names = line[1:].split()
        elif line.strip():
            v = line.split()
            kcreep_rows[float(v[0])] = {n: (float(x) if n != "verdict" else x) for n, x in zip(names, v)}

print("# shift  y_rail  y_wheel  delta  r_wheel  hertz_length  hertz_width   (independent)"
      + ("   | kcreep: y_rail y_wheel delta r_wheel length width" if wr else ""))
result = {}
for shift in range(-6, 11):
    z_wheel = wheel.envelope(grid - origin - shift, True)           # the wheel at height 0
    d = z_rail - z_wheel
    d[np.isnan(d)] = np.inf
    k = int(np.argmin(d))
    a, b, c = d[k - 1], d[k], d[k + 1]
    t = (a - c) / (2 * (a + c - 2 * b)) if a + c - 2 * b > 0 else 0.0
    y = grid[k] + t * step
    y_rail = y - rail_dy
    y_wheel = y - origin - shift
    zr, dzr, d2zr = rail.at_y(y_rail, False)
    zw, dzw, d2zw = wheel.at_y(y_wheel, True)
    delta = math.atan(-dzr)
    r_wheel = r_nom + zw
    # curvatures in the contact plane: along x the wheel's rolling radius (its normal section:
    # r / cos(delta)); across, the profiles' curvature measured along their arc
    kr = d2zr / (1 + dzr ** 2) ** 1.5             # rail: z down, a crown has d2z > 0 ... (positive: convex)
    kw = -d2zw / (1 + dzw ** 2) ** 1.5            # wheel: concave tread, negative
    A = math.cos(delta) / (2 * r_wheel)
    B = (kr + kw) / 2
    fn = 80000 / math.cos(delta)
    length = width = float("nan")
    if B > 0:
        ax, by = hertz(A, B, fn, 82000.0, 0.28)
        length, width = 2 * ax, 2 * by
    result[shift] = (y_rail, y_wheel, delta, r_wheel)
    line = f"{shift:6.1f} {y_rail:8.3f} {y_wheel:8.3f} {delta:7.4f} {r_wheel:8.3f} {length:8.2f} {width:8.2f}"
    if shift in kcreep_rows:
        r = kcreep_rows[shift]
        line += (f"   | {r['y_rail']:8.3f} {r['y_wheel']:8.3f} {r['delta']:7.4f} {r['r_wheel']:8.3f} "
                 f"{r['length']:7.2f} {r['width']:7.2f}")
    print(line)
print("# rolling radius difference r(y) - r(-y) of a symmetric wheelset (mm)")
for s in range(1, 7):
    dr = result[s][3] - result[-s][3]
    line = f"{s:6.1f} {dr:8.4f}"
    if s in kcreep_rows and -s in kcreep_rows:
        line += f"   | kcreep {kcreep_rows[s]['r_wheel'] - kcreep_rows[-s]['r_wheel']:8.4f}"
    print(line)
