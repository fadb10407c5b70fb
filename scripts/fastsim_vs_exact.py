#!/usr/bin/env python3
"""FASTSIM against the exact steady-rolling solver on generated patches (issue 30).

  scripts/fastsim_vs_exact.py [--kcreep build/kcreep] [--doc docs/fastsim.md | --no-doc]
                              [--csv FILE] [--work DIR [--reuse]] [--patches N] [--lock FILE]

Generates 110 patches (seeded: the same every run):
  - 30 ellipses, a/b from 0.2 to 5 (log-spaced), nu from 0 to 0.5, Hertz's pressure;
  - 50 masks: the five shapes of scripts/make_shapes.py (two_lobed, crescent, twin,
    rectangle, superellipse) stretched, squeezed and mirrored (4 each, at their own
    places), and kidneys, horseshoes, L shapes, wedges, ellipses with holes,
    star-shaped blobs, two ellipses one behind the other or side by side,
    superellipses (3-4 each, centroid at the spin centre); the parabolic strip
    pressure (the model kcreep uses on a bare mask);
  - 30 gaps through the normal problem (approach given, the normal solve's
    pressure): paraboloids with curvature ratio 0.2 to 5, two-point gaps (two
    lateral radii and a step between them), gaps flattened laterally (y^4), egg
    shapes (curvature changing along x or y), and the worn wheel on a rail of
    input/wheel_rail.gap at five approaches.
Every patch is solved on its own grid (target_error = 0, 870-2900 cells) and
run with &rolling and with &fastsim (flexibility = 'all': the exact L and the
two equivalent ellipses' L) under each rule ('separate', 'weighted',
'aligned') at the same 77 creepages: 11 directions, 3 pure (xi, eta, phi) and
8 combined, each at 7 levels s = 0.1 .. 4 of the linear theory's size
|(f11 xi, f22 eta, f22 c phi)| / (mu Fn) (c = sqrt(area/pi): spin as the
lateral creepage c phi), from small creepage to saturation. The error of a
point is |F - F_exact| / (mu Fn), F = (Fx, Fy), as the summary of a run with
both groups prints it. A numpy copy of kcreep's FASTSIM (checked against
kcreep's creep tables on every patch) adds variants: the -phi y term with L1
or L4 (fastsim.md, "Against CONTACT"), the aligned rule's ingredients one at a time,
and other slip steps.

Every kcreep run holds --lock (default /tmp/kcreep-bench.lock; 'none': no
lock) and runs with OMP_NUM_THREADS=1: about 4 minutes of one CPU.
Writes the tables into the section `fastsim_vs_exact` of --doc (replaced on
rerun), prints them, and with --csv one line per point, rule and source.
--work keeps the runs in a folder; --reuse with it skips runs whose namelist
is unchanged. --patches N: only the first N patches of each family (a quick
look; the doc is not written). Needs numpy (/usr/bin/python3 on these
machines); --help needs nothing but the standard library."""
import argparse
import math
import os
import random
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MU = 0.3
LEVELS = (0.1, 0.25, 0.5, 0.8, 1.2, 2.0, 4.0)
# creepage directions (a, b, d), normalised: xi = a s mu Fn / f11, eta = b s mu Fn / f22,
# phi = d s mu Fn / (f22 c), c = sqrt(area / pi) (creepages_of)
DIRECTIONS = [(1, 0, 0), (0, 1, 0), (0, 0, 1),
              (1, 1, 0), (1, -1, 0), (0, 1, 1), (0, 1, -1), (1, 0, 1), (1, 0, -1), (1, 1, 1), (-1, 2, -1)]
SOURCES = ('exact', 'ellipse-box', 'ellipse-moments')
RULES = ('aligned', 'separate', 'weighted')   # kcreep's rules; the first run carries &rolling


# ---------------------------------------------------------------- patches
def shapes_module():
    """scripts/make_shapes.py's inside(shape, x, y), imported without running its command line."""
    import importlib.util
    spec = importlib.util.spec_from_file_location('make_shapes', os.path.join(HERE, 'scripts', 'make_shapes.py'))
    module = importlib.util.module_from_spec(spec)
    argv, sys.argv = sys.argv, sys.argv[:1]
    try:
        spec.loader.exec_module(module)
    finally:
        sys.argv = argv
    return module


def mask_text(inside, target_cells, centre=False):
    """Mask file text of the region inside(x, y) (bounded, within |x|, |y| < 40) on square cells
    chosen so that it has about target_cells cells; one empty cell around it. centre: the region
    moved so that its centroid is the origin (the spin centre)."""
    # extent and area on a coarse sample
    n = 240
    xs = [-40 + 80 * (i + 0.5) / n for i in range(n)]
    hits = [(x, y) for x in xs for y in xs if inside(x, y)]
    if not hits:
        raise ValueError('empty shape')
    if centre:
        cx, cy = sum(p[0] for p in hits) / len(hits), sum(p[1] for p in hits) / len(hits)
        hits = [(x - cx, y - cy) for x, y in hits]
        shape = inside
        inside = lambda x, y: shape(x + cx, y + cy)  # noqa: E731
    area = len(hits) * (80 / n) ** 2
    h = math.sqrt(area / target_cells)
    for _ in range(3):
        x_lo = min(p[0] for p in hits) - 80 / n
        x_hi = max(p[0] for p in hits) + 80 / n
        y_lo = min(p[1] for p in hits) - 80 / n
        y_hi = max(p[1] for p in hits) + 80 / n
        mx = int((x_hi - x_lo) / h) + 3
        my = int((y_hi - y_lo) / h) + 3
        x0 = (x_lo + x_hi) / 2 - (mx - 1) * h / 2
        y0 = (y_lo + y_hi) / 2 - (my - 1) * h / 2
        rows = [''.join('#' if inside(x0 + ix * h, y0 + iy * h) else '.' for ix in range(mx)) for iy in range(my)]
        cells = sum(r.count('#') for r in rows)
        if abs(cells / target_cells - 1) < 0.15:
            break
        h *= math.sqrt(cells / target_cells)
    return f'{mx} {my} {h:.10g} {h:.10g} {x0:.10g} {y0:.10g}\n' + '\n'.join(rows) + '\n', cells


def generate_patches(rng, per_family=None):
    """[(family, name, description, namelist head, files {name: text})]; namelist head: &patch .. &solver."""
    shapes = shapes_module()
    ellipses, masks, gaps = [], [], []
    # ellipses: a/b log-spaced 0.2 .. 5, nu from a shuffled set, c = 1, ~1500 cells on near-square cells
    ratios = [0.2 * 25 ** (k / 29) for k in range(30)]
    nus = [0.0, 0.1, 0.2, 0.25, 0.28, 0.3, 0.4, 0.5] * 4
    rng.shuffle(nus)
    for k, r in enumerate(ratios):
        a, b = math.sqrt(r), 1 / math.sqrt(r)
        h = math.sqrt(math.pi * a * b / 1500)
        mx, my = max(8, round(2 * a / h)), max(8, round(2 * b / h))
        head = (f"&patch shape = 'ellipse', semi_a = {a:.10g}, semi_b = {b:.10g}, mx = {mx}, my = {my} /\n"
                f"&material g = 1, nu = {nus[k]} /\n&solver target_error = 0 /\n")
        ellipses.append(('ellipse', f'ellipse{k:02d}', f'a/b = {r:.3g}, nu = {nus[k]}', head, {}, 'hertz'))

    # masks: make_shapes' five shapes transformed, and parametric shapes
    def add_mask(name, desc, inside, centre=False):
        text, cells = mask_text(inside, rng.randint(900, 1500), centre)
        head = (f"&patch shape = 'mask', mask_file = '{name}.mask' /\n"
                f"&material g = 1, nu = {rng.choice([0.0, 0.25, 0.28, 0.3, 0.5])} /\n&solver target_error = 0 /\n")
        masks.append(('mask', name, desc, head, {f'{name}.mask': text}, 'parabolic'))

    for shape in ('two_lobed', 'crescent', 'twin', 'rectangle', 'superellipse'):
        for k in range(4):
            sx, sy = rng.uniform(0.6, 1.6), rng.uniform(0.6, 1.6)
            fx, fy = (-1 if k % 2 else 1), (-1 if k >= 2 else 1)

            def inside(x, y, shape=shape, sx=sx, sy=sy, fx=fx, fy=fy):
                return shapes.inside(shape, fx * x / sx, fy * y / sy)
            add_mask(f'{shape}{k}', f'make_shapes {shape}, x*{sx:.2f}{" mirrored" if fx < 0 else ""}, '
                     f'y*{sy:.2f}{" mirrored" if fy < 0 else ""}', inside)

    def kidney(s, t):      # an ellipse with a bite out of one side (bite toward +x, -x, +y or -y)
        ax, ay, cr = rng.uniform(3, 5), rng.uniform(3, 5), rng.uniform(1.5, 3)
        d = [(1, 0), (-1, 0), (0, 1), (0, -1)][t]
        cx, cy = d[0] * (ax + cr * 0.4), d[1] * (ay + cr * 0.4)
        return (f'kidney, bite toward {"+x -x +y -y".split()[t]}',
                lambda x, y: (x / ax) ** 2 + (y / ay) ** 2 <= 1 and (x - cx) ** 2 + (y - cy) ** 2 > (cr * 1.3) ** 2)

    def horseshoe(s, t):   # a ring sector open toward one side
        r1, r2 = rng.uniform(2, 3), rng.uniform(4, 5.5)
        half = rng.uniform(0.5, 1.1)
        open_angle = [0, math.pi, math.pi / 2, -math.pi / 2][t]

        def inside(x, y):
            r = math.hypot(x, y)
            ang = math.atan2(y, x) - open_angle
            ang = (ang + math.pi) % (2 * math.pi) - math.pi
            return r1 <= r <= r2 and abs(ang) > half
        return f'horseshoe open toward {"+x -x +y -y".split()[t]}', inside

    def lshape(s, t):
        w, l1, l2 = rng.uniform(2, 3), rng.uniform(6, 9), rng.uniform(6, 9)
        fx, fy = (1 if t % 2 == 0 else -1), (1 if t < 2 else -1)
        return (f'L shape ({fx:+d}, {fy:+d})',
                lambda x, y: (0 <= fx * x <= l1 and 0 <= fy * y <= w) or (0 <= fx * x <= w and 0 <= fy * y <= l2))

    def wedge(s, t):       # a triangle pointing toward +x, -x, +y or -y
        length, half = rng.uniform(6, 10), rng.uniform(2.5, 4.5)
        sgn = 1 if t % 2 == 0 else -1
        if t < 2:
            return (f'wedge pointing toward {"+x" if sgn > 0 else "-x"}',
                    lambda x, y: 0 <= sgn * x <= length and abs(y) <= half * (1 - sgn * x / length))
        return (f'wedge pointing toward {"+y" if sgn > 0 else "-y"}',
                lambda x, y: 0 <= sgn * y <= length and abs(x) <= half * (1 - sgn * y / length))

    def ring(s, t):        # an ellipse with an elliptic hole, the hole off centre for t > 0
        ax, ay = rng.uniform(3.5, 5.5), rng.uniform(3.5, 5.5)
        hx, hy = ax * rng.uniform(0.3, 0.5), ay * rng.uniform(0.3, 0.5)
        ox, oy = [(0, 0), (ax * 0.3, 0), (0, ay * 0.3), (-ax * 0.3, 0)][t]
        return (f'ellipse with a hole at ({ox:.1f}, {oy:.1f})',
                lambda x, y: (x / ax) ** 2 + (y / ay) ** 2 <= 1 and ((x - ox) / hx) ** 2 + ((y - oy) / hy) ** 2 > 1)

    def blob(s, t):        # star-shaped: r(theta) = r0 (1 + sum a_k cos(k theta + p_k))
        coef = [(k, rng.uniform(0.05, 0.22), rng.uniform(0, 2 * math.pi)) for k in range(2, 6)]

        def inside(x, y):
            th = math.atan2(y, x)
            return math.hypot(x, y) <= 4 * (1 + sum(a * math.cos(k * th + p) for k, a, p in coef))
        return 'star-shaped blob (modes 2-5)', inside

    def pair(s, t):        # two ellipses, one behind the other (t = 0, 1) or side by side (t = 2, 3)
        a1, b1, a2, b2 = (rng.uniform(1.5, 3.5) for _ in range(4))
        gap = rng.uniform(0.3, 2.0)
        if t < 2:
            c1, c2 = (a1 + gap / 2, rng.uniform(-1, 1)), (-(a2 + gap / 2), rng.uniform(-1, 1))
            desc = 'two ellipses one behind the other (strips with two segments)'
        else:
            c1, c2 = (rng.uniform(-1, 1), b1 + gap / 2), (rng.uniform(-1, 1), -(b2 + gap / 2))
            desc = 'two ellipses side by side'
        return desc, lambda x, y: (((x - c1[0]) / a1) ** 2 + ((y - c1[1]) / b1) ** 2 <= 1 or
                                   ((x - c2[0]) / a2) ** 2 + ((y - c2[1]) / b2) ** 2 <= 1)

    def superellipse(s, t):
        ax, ay, p = rng.uniform(2.5, 6), rng.uniform(2.5, 6), rng.choice([1.2, 1.5, 3, 5, 8])
        return (f'superellipse |x/{ax:.1f}|^{p} + |y/{ay:.1f}|^{p} <= 1',
                lambda x, y: abs(x / ax) ** p + abs(y / ay) ** p <= 1)

    families = [('kidney', kidney), ('horseshoe', horseshoe), ('lshape', lshape), ('wedge', wedge), ('ring', ring),
                ('blob', blob), ('pair', pair), ('superell', superellipse)]
    for name, make in families:
        for t in range(4 if name not in ('blob', 'superell') else 3):
            desc, inside = make(None, t)
            add_mask(f'{name}{t}', desc + ', centroid at the spin centre', inside, centre=True)

    # gaps (mm, steel): approach given; the grid from the interpenetration region, ~1000-1500 contact cells
    def add_gap(name, desc, h, approach, nu=0.28):
        text = gap_text(h, approach)
        head = (f"&patch shape = 'gap' /\n&material g = 82000, nu = {nu} /\n"
                f"&normal gap_file = '{name}.gap', approach = {approach} /\n&solver target_error = 0 /\n")
        gaps.append(('gap', name, desc, head, {f'{name}.gap': text}, 'normal'))

    for k, ratio in enumerate([0.2, 0.35, 0.6, 1.0, 1.7, 3.0, 5.0]):
        rx, ry = 300 * math.sqrt(ratio), 300 / math.sqrt(ratio)
        add_gap(f'paraboloid{k}', f'paraboloid rx/ry = {ratio}', lambda x, y, rx=rx, ry=ry: x * x / (2 * rx) + y * y / (2 * ry),
                0.05, nu=rng.choice([0.0, 0.28, 0.5]))
    for k in range(8):
        rx, r1, r2 = rng.uniform(250, 500), rng.uniform(80, 300), rng.uniform(80, 300)
        d, step = rng.uniform(3, 7), rng.uniform(0, 0.03)
        approach = rng.uniform(0.03, 0.08)

        def h(x, y, rx=rx, r1=r1, r2=r2, d=d, step=step):
            return x * x / (2 * rx) + min((y - d) ** 2 / (2 * r1), (y + d) ** 2 / (2 * r2) + step)
        add_gap(f'twopoint{k}', f'two-point gap, lateral radii {r1:.0f} and {r2:.0f} mm {2 * d:.1f} mm apart, '
                f'step {step:.3f} mm, approach {approach:.3f} mm', h, round(approach, 4))
    for k in range(4):
        rx, k4 = rng.uniform(150, 500), rng.uniform(2e-4, 2e-3)
        add_gap(f'flat{k}', f'flattened laterally: x^2/(2 {rx:.0f}) + {k4:.1e} y^4',
                lambda x, y, rx=rx, k4=k4: x * x / (2 * rx) + k4 * y ** 4, 0.04)
    for k in range(6):
        rx, ry, kk, w = rng.uniform(200, 400), rng.uniform(200, 400), rng.uniform(0.4, 0.8), rng.uniform(2, 5)
        if k % 2 == 0:   # curvature changing along x (across the rolling direction's leading/trailing halves)
            desc = f'egg along x: x^2 (1 + {kk:.2f} tanh(x/{w:.1f}))/(2 {rx:.0f}) + y^2/(2 {ry:.0f})'
            h = (lambda x, y, rx=rx, ry=ry, kk=kk, w=w, s=(1 if k % 4 == 0 else -1):
                 x * x * (1 + s * kk * math.tanh(x / w)) / (2 * rx) + y * y / (2 * ry))
        else:
            desc = f'egg along y: x^2/(2 {rx:.0f}) + y^2 (1 + {kk:.2f} tanh(y/{w:.1f}))/(2 {ry:.0f})'
            h = (lambda x, y, rx=rx, ry=ry, kk=kk, w=w:
                 x * x / (2 * rx) + y * y * (1 + kk * math.tanh(y / w)) / (2 * ry))
        add_gap(f'egg{k}', desc, h, 0.05)
    wheel = os.path.join(HERE, 'input', 'wheel_rail.gap')
    for k, approach in enumerate([0.04, 0.055, 0.07, 0.0876, 0.105]):
        head = (f"&patch shape = 'gap' /\n&normal gap_file = '{wheel}', approach = {approach},\n"
                "        e1 = 210000.0, nu1 = 0.28, e2 = 210000.0, nu2 = 0.28 /\n&solver target_error = 0 /\n")
        gaps.append(('gap', f'wheelrail{k}', f'worn wheel on rail (input/wheel_rail.gap), approach {approach} mm',
                     head, {}, 'normal'))
    if per_family:
        ellipses, masks, gaps = ellipses[:per_family], masks[:per_family], gaps[:per_family]
    return ellipses + masks + gaps


def gap_text(h, approach, target=2600):
    """Gap file text of h(x, y) over the region h < approach widened by 25 % (plus two cells), square
    cells such that that region holds about target cells."""
    n = 200
    lim = 40.0
    for _ in range(4):      # zoom in on the interpenetration region
        xs = [-lim + 2 * lim * (i + 0.5) / n for i in range(n)]
        hits = [(x, y) for x in xs for y in xs if h(x, y) < approach]
        ext = max(max(abs(p[0]), abs(p[1])) for p in hits) + 2 * lim / n
        if ext > 0.6 * lim:
            break
        lim = ext * 1.2
    area = len(hits) * (2 * lim / n) ** 2
    cell = math.sqrt(area / target)
    x_lo, x_hi = min(p[0] for p in hits), max(p[0] for p in hits)
    y_lo, y_hi = min(p[1] for p in hits), max(p[1] for p in hits)
    wx, wy = x_hi - x_lo, y_hi - y_lo
    x_lo, x_hi, y_lo, y_hi = x_lo - 0.125 * wx - 2 * cell, x_hi + 0.125 * wx + 2 * cell, \
        y_lo - 0.125 * wy - 2 * cell, y_hi + 0.125 * wy + 2 * cell
    mx, my = int((x_hi - x_lo) / cell) + 1, int((y_hi - y_lo) / cell) + 1
    x0, y0 = (x_lo + x_hi) / 2 - (mx - 1) * cell / 2, (y_lo + y_hi) / 2 - (my - 1) * cell / 2
    lines = [f'{mx} {my} {cell:.10g} {cell:.10g} {x0:.10g} {y0:.10g}']
    for iy in range(my):
        lines.append(' '.join(f'{h(x0 + ix * cell, y0 + iy * cell):.10e}' for ix in range(mx)))
    return '\n'.join(lines) + '\n'


# ---------------------------------------------------------------- running kcreep
CPU = [0.0]   # CPU seconds of the kcreep runs (kept beside a run for --reuse)


def run_kcreep(args, folder, name, text):
    """kcreep on the namelist text (folder/name.nml) under the lock, one thread; its standard output.
    With --reuse, a run whose namelist is unchanged and finished before is not repeated."""
    import resource
    path = os.path.join(folder, name + '.nml')
    done = os.path.join(folder, name + '.done')
    if args.reuse and os.path.exists(done) and os.path.exists(path) and open(path).read() == text:
        lines = open(done).read().split('\n', 1)
        CPU[0] += float(lines[0].split()[-1])
        return lines[1]
    with open(path, 'w') as f:
        f.write(text)
    env = dict(os.environ, OMP_NUM_THREADS='1')
    cmd = ([] if args.lock in ('', 'none') else ['flock', args.lock]) + [args.kcreep, name + '.nml']
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    r = subprocess.run(cmd, cwd=folder, env=env, capture_output=True, text=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if r.returncode != 0:
        raise RuntimeError(f'kcreep failed on {name} (exit {r.returncode}): {r.stderr.strip()[-600:]}')
    cpu = after.ru_utime + after.ru_stime - before.ru_utime - before.ru_stime
    CPU[0] += cpu
    with open(done, 'w') as f:
        f.write(f'# CPU seconds {cpu:.3f}\n' + r.stdout)
    return r.stdout


def numbers(path):
    """Data rows (lists of words) of a kcreep table."""
    return [line.split() for line in open(path) if line.strip() and not line.startswith('#')]


def read_first_map(path):
    """(ix, iy, x, y, pn) of the cells of the first block of a rolling map file."""
    cells = []
    with open(path) as f:
        for line in f:
            if line.startswith('#'):
                if cells:
                    break
                continue
            if not line.strip():
                if cells:
                    break
                continue
            w = line.split()
            cells.append((int(w[0]), int(w[1]), float(w[2]), float(w[3]), float(w[4])))
    return cells


def creepages_of(tab, fn, subset=None):
    """The study's creepages [((xi, eta, phi), direction index, level)] for a patch's f11, f22 and
    c = sqrt(area/pi): direction (a, b, d) at level s is xi = a k/f11, eta = b k/f22,
    phi = d k/(f22 c), k = s mu Fn / |(a, b, d)|: the spin as the lateral creepage c phi, as Kalker's
    weighted rule measures it (f23, the net lateral force of spin, can be small or negative on a
    patch off its spin centre while the slip of spin is not). subset: only these (direction, level)."""
    out = []
    for d, (a, b, c) in enumerate(DIRECTIONS):
        norm = math.sqrt(a * a + b * b + c * c)
        for s in LEVELS:
            if subset is not None and (d, s) not in subset:
                continue
            k = s * MU * fn / norm
            creep = (a * k / tab['f11'], b * k / tab['f22'], c * k / (tab['f22'] * tab['c']))
            out.append((tuple(float(f'{v:.12e}') for v in creep), d, s))   # as the namelist gives them
    return out


def run_patch(args, folder, patch, subset=None):
    """&rolling and &fastsim (every rule) on one patch at its creepages (subset: creepages_of's);
    returns a dict with the coefficients, the points, the forces and the patch cells."""
    from kcreep import table
    family, name, desc, head, files, pressure = patch
    for fname, text in files.items():
        with open(os.path.join(folder, fname), 'w') as f:
            f.write(text)
    t0 = time.time()
    run_kcreep(args, folder, name + '_c', head)
    tab = table.read(os.path.join(folder, name + '_c.tab'))[0]
    fn = tab['fn'] if family == 'gap' else 1.0
    points = creepages_of(tab, fn, subset)
    creep = ',\n  '.join(' '.join(f'{v:.12e}' for v in p[0]) for p in points)
    groups = {}
    for rule in RULES:
        text = head + f"&fastsim mu = {MU}, flexibility = 'all', rule = '{rule}', pressure = '{pressure}',\n  creepages = {creep} /\n"
        if rule == RULES[0]:
            text += (f"&output creep_file = '{name}_{rule}.creep', rolling_file = '{name}.roll', "
                     f"rolling_map_file = '{name}.rollmap' /\n")
            text += f"&rolling mu = {MU}, pressure = '{pressure}', maps = .true.,\n  creepages = {creep} /\n"
        else:
            text += f"&output creep_file = '{name}_{rule}.creep' /\n"
        groups[rule] = run_kcreep(args, folder, f'{name}_{rule}', text)
    seconds = time.time() - t0
    roll = [[float(v) for v in w] for w in numbers(os.path.join(folder, name + '.roll'))]
    fast = {}
    for rule in RULES:
        rows = numbers(os.path.join(folder, f'{name}_{rule}.creep'))
        for k, w in enumerate(rows):
            fast[(rule, w[8], k // len(SOURCES))] = (float(w[3]), float(w[4]), float(w[5]))
    # the patch cells and their pressure: the first block of the rolling maps (kept, the maps go)
    maps, keep = os.path.join(folder, name + '.rollmap'), os.path.join(folder, name + '.cells')
    if os.path.exists(maps):
        with open(keep, 'w') as f:
            f.write(''.join(f'{c[0]} {c[1]} {c[2]!r} {c[3]!r} {c[4]!r}\n' for c in read_first_map(maps)))
        os.remove(maps)
    cells = [(int(w[0]), int(w[1]), float(w[2]), float(w[3]), float(w[4])) for w in numbers(keep)]
    lines = [line.strip() for line in groups[RULES[0]].splitlines() if 'against exact' in line]
    summary = [line for line in lines if line.startswith('FASTSIM')]
    fast_model = [line for line in lines if line.startswith('fast model')]
    return dict(family=family, name=name, desc=desc, tab=tab, points=points, roll=roll, fast=fast,
                cells=cells, seconds=seconds, summary=summary, fast_model=fast_model, n=int(tab['n']))


def point_errors(res):
    """{(rule, source): [|F - F_exact| / (mu Fn) of each point]} of kcreep's rules, F = (Fx, Fy)."""
    out = {}
    for q, row in enumerate(res['roll']):
        for rule in RULES:
            for src in SOURCES:
                fx, fy, _ = res['fast'][(rule, src, q)]
                out.setdefault((rule, src), []).append(math.hypot(fx - row[3], fy - row[4]) / (MU * row[6]))
    return out


# ---------------------------------------------------------------- numpy FASTSIM (kcreep_fastsim_forces)
def fastsim_np(np, cells, mu, sx, sy, rx, ry, metric=None, slip_slopes=None, slip_metric=None, creep=None):
    """kcreep's FASTSIM for P points at once: dp/dx = (sx - rx y, sy + ry x) per point (arrays of P);
    cells: (ix, iy, x, y, pn). metric: None, Kalker's slip step (the predictor scaled onto the bound),
    or a function (xe (P, my), y (my,)) -> (Dx, Dy) (P, my): the slipping traction is the point of the
    bound nearest to the predictor in the norm sum D_k p_k^2. Returns (fx, fy, mz) arrays of P and the grid."""
    ix = np.array([c[0] for c in cells]) - 1
    iy = np.array([c[1] for c in cells]) - 1
    xs, ys, pn = (np.array([c[k] for c in cells]) for k in (2, 3, 4))
    mx, my = ix.max() + 1, iy.max() + 1
    dx = (xs.max() - xs.min()) / max(1, ix.max() - ix.min()) if ix.max() > ix.min() else 1.0
    dy = (ys.max() - ys.min()) / max(1, iy.max() - iy.min()) if iy.max() > iy.min() else 1.0
    x0, y0 = xs[0] - ix[0] * dx, ys[0] - iy[0] * dy
    inside = np.zeros((my, mx + 1), bool)
    inside[iy, ix] = True
    press = np.zeros((my, mx))
    press[iy, ix] = pn
    yrow = y0 + np.arange(my) * dy
    h = dx / 2
    P = len(sx)
    sx, sy, rx, ry = (np.asarray(v, float)[:, None] for v in (sx, sy, rx, ry))
    tx, ty = np.zeros((P, my)), np.zeros((P, my))
    fx, fy, mz = np.zeros(P), np.zeros(P), np.zeros(P)
    for i in range(mx - 1, -1, -1):
        m = inside[:, i]
        if not m.any():
            continue
        lead = m & ~inside[:, i + 1]
        x = x0 + i * dx
        step = np.where(lead, h, dx)[None, :]
        xe = np.where(lead, x + h / 3, x + h)[None, :]
        tx = np.where(lead[None, :], 0.0, tx)
        ty = np.where(lead[None, :], 0.0, ty)
        gx = tx - step * (sx - rx * yrow[None, :])
        gy = ty - step * (sy + ry * xe)
        bound = mu * np.maximum(press[:, i], 0)[None, :]
        mag = np.hypot(gx, gy)
        slip = mag > bound
        if slip_slopes is not None:   # the slipping cells' traction from another predictor
            s2x, s2y, r2x, r2y = (np.asarray(v, float)[:, None] for v in slip_slopes)
            hx = tx - step * (s2x - r2x * yrow[None, :])
            hy = ty - step * (s2y + r2y * xe)
            gx, gy = np.where(slip, hx, gx), np.where(slip, hy, gy)
            mag = np.hypot(gx, gy)
            slip = slip & (mag > bound)
        if slip_metric is not None:   # slipping cells: p_prev - step D^-1 w, projected in the D norm
            xi, eta, phi = (np.asarray(v, float)[:, None] for v in creep)
            ddx, ddy = slip_metric(np.broadcast_to(xe, gx.shape), yrow)
            hx = tx - step * (xi - phi * yrow[None, :]) / ddx
            hy = ty - step * (eta + phi * xe) / ddy
            gx, gy = np.where(slip, hx, gx), np.where(slip, hy, gy)
            mag = np.hypot(gx, gy)
            slip = slip & (mag > bound)
            metric = slip_metric
        if metric is None:
            scale = np.where(slip, bound / np.where(mag > 0, mag, 1), 1.0)
            gx, gy = gx * scale, gy * scale
        elif slip.any():
            # the point of the bound nearest to the predictor in the D norm (kcreep_fastsim_forces aligned_slip):
            # p_k = D_k q_k / (D_k + lam), Newton on 1/g - 1/|p(lam)| from lam = 0, on the slipping cells only
            ddx, ddy = (np.broadcast_to(v, gx.shape) for v in metric(np.broadcast_to(xe, gx.shape), yrow))
            bnd = np.broadcast_to(bound, gx.shape)
            k = np.nonzero(slip)
            qx, qy, dx_, dy_, g_ = gx[k], gy[k], ddx[k], ddy[k], bnd[k]
            pos = g_ > 0
            g1 = np.where(pos, g_, 1)
            lam = np.zeros_like(qx)
            for _ in range(60):
                px, py = dx_ * qx / (dx_ + lam), dy_ * qy / (dy_ + lam)
                r = np.hypot(px, py)
                if np.all(np.abs(r - g1)[pos] <= 1e-14 * g1[pos]):
                    break
                dr = -(px * px / (dx_ + lam) + py * py / (dy_ + lam)) / r
                lam = np.where(pos, lam - (1 / g1 - 1 / r) / (dr / r ** 2), lam)
            px, py = dx_ * qx / (dx_ + lam), dy_ * qy / (dy_ + lam)
            r = np.hypot(px, py)
            gx, gy = gx.copy(), gy.copy()
            gx[k] = np.where(pos, px * g1 / r, 0.0)
            gy[k] = np.where(pos, py * g1 / r, 0.0)
        tx = np.where(m[None, :], gx, tx)
        ty = np.where(m[None, :], gy, ty)
        fx += (gx * m).sum(axis=1)
        fy += (gy * m).sum(axis=1)
        mz += ((x * gy - yrow[None, :] * gx) * m).sum(axis=1)
    da = dx * dy
    return fx * da, fy * da, mz * da, dict(inside=inside[:, :mx], dx=dx, dy=dy, x0=x0, y0=y0)


def spin_x_flexibility(np, g, l3, f33):
    """kcreep_fastsim_forces spin_x_flexibility: L4 of the -phi y term such that f33 is exact (NaN if none)."""
    inside, dx, dy, x0, y0 = g['inside'], g['dx'], g['dy'], g['x0'], g['y0']
    h = dx / 2
    j2 = j3 = 0.0
    my, mx = inside.shape
    for iy in range(my):
        y = y0 + iy * dy
        xl = 0.0
        for ix in range(mx - 1, -1, -1):
            if not inside[iy, ix]:
                continue
            x = x0 + ix * dx
            if ix == mx - 1 or not inside[iy, ix + 1]:
                xl = x + h
            j2 += (y * y + dy * dy / 12) * 2 * h * (xl - x)
            j3 += xl * xl * x * h - (x ** 3 * h + x * h ** 3)
    j2 *= dy
    j3 *= dy
    return j2 / (f33 - j3 / l3) if f33 > j3 / l3 else float('nan')


def variants(np, res):
    """FASTSIM with the exact L, computed here: kcreep's three rules (to check this copy against
    kcreep's creep tables) and the variants; {rule: (fx, fy, mz) arrays of the points}."""
    l1, l2, l3 = res['tab']['L1'], res['tab']['L2'], res['tab']['L3']   # all digits (the creep table has 7)
    c_len = res['tab']['c']
    xi, eta, phi = (np.array([p[0][k] for p in res['points']]) for k in range(3))
    cells = res['cells']
    one = np.ones((len(xi), 1))

    def per_point(dx, dy):
        return lambda xe, y: (np.broadcast_to(dx[:, None] * one, xe.shape), np.broadcast_to(dy[:, None] * one, xe.shape))

    def per_cell(xe, y):       # the flexibilities of the terms of a component weighted by their rigid slip there
        ax, ay = abs(xi[:, None]) + 0 * y[None, :], abs(eta[:, None]) + 0 * xe
        bx, by = abs(phi[:, None] * y[None, :]), abs(phi[:, None] * xe)
        return (np.where(ax + bx > 0, (ax * l1 + bx * abs(l3)) / np.where(ax + bx > 0, ax + bx, 1), l1),
                np.where(ay + by > 0, (ay * l2 + by * abs(l3)) / np.where(ay + by > 0, ay + by, 1), l2))

    sep = (xi / l1, eta / l2, phi / l3, phi / l3)
    lw = (abs(xi) * l1 + abs(eta) * l2 + c_len * abs(phi) * l3) / np.sqrt(xi ** 2 + eta ** 2 + (c_len * phi) ** 2)
    # the aligned rule's D (kcreep_fastsim_forces aligned_slip_flexibility: the L by their size)
    wx = np.where(abs(xi) + abs(phi) > 0, (abs(xi) * l1 + c_len * abs(phi) * abs(l3)) /
                  np.where(abs(xi) + abs(phi) > 0, abs(xi) + c_len * abs(phi), 1), l1)
    wy = np.where(abs(eta) + abs(phi) > 0, (abs(eta) * l2 + c_len * abs(phi) * abs(l3)) /
                  np.where(abs(eta) + abs(phi) > 0, abs(eta) + c_len * abs(phi), 1), l2)
    out = {}
    fx, fy, mz, g = fastsim_np(np, cells, MU, *sep)
    out['separate'] = (fx, fy, mz)
    out['weighted'] = fastsim_np(np, cells, MU, xi / lw, eta / lw, phi / lw, phi / lw)[:3]
    out['aligned'] = fastsim_np(np, cells, MU, xi / l1, eta / l2, phi / wx, phi / abs(l3), creep=(xi, eta, phi),
                                slip_metric=per_point(wx, wy))[:3]
    # fastsim.md, "Against CONTACT": the L of the -phi y term
    out['separate, -phi y with L1'] = fastsim_np(np, cells, MU, xi / l1, eta / l2, phi / l1, phi / l3)[:3]
    l4 = spin_x_flexibility(np, g, l3, res['tab']['f33'])
    if math.isfinite(l4) and l4 > 0:
        out['separate, -phi y with L4 (f33 exact)'] = fastsim_np(np, cells, MU, xi / l1, eta / l2, phi / l4,
                                                                 phi / l3)[:3]
    # other slip steps after the separate rule's adhesion predictor
    out['separate; slip: weighted L'] = fastsim_np(np, cells, MU, *sep,
                                                   slip_slopes=(xi / lw, eta / lw, phi / lw, phi / lw))[:3]
    out['separate; slip: D = diag(L1, L2)'] = fastsim_np(np, cells, MU, *sep, creep=(xi, eta, phi),
                                                         slip_metric=per_point(l1 + 0 * xi, l2 + 0 * xi))[:3]
    # the aligned rule's ingredients one by one, and other slip steps
    out['aligned, -phi y with L3'] = fastsim_np(np, cells, MU, *sep, creep=(xi, eta, phi),
                                                slip_metric=per_point(wx, wy))[:3]
    out['aligned, -phi y and Dx with L1'] = fastsim_np(np, cells, MU, xi / l1, eta / l2, phi / l1, phi / abs(l3),
                                                       creep=(xi, eta, phi), slip_metric=per_point(l1 + 0 * xi, wy))[:3]
    out['aligned, D per cell'] = fastsim_np(np, cells, MU, xi / l1, eta / l2, phi / wx, phi / abs(l3), creep=(xi, eta, phi),
                                            slip_metric=per_cell)[:3]
    out['separate; slip: its predictor projected in the D norm'] = fastsim_np(np, cells, MU, *sep,
                                                                              metric=per_point(wx, wy))[:3]
    return out


# ---------------------------------------------------------------- main
def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0], formatter_class=argparse.RawDescriptionHelpFormatter,
                                 epilog=__doc__)
    ap.add_argument('--kcreep', default=os.path.join(HERE, 'build', 'kcreep'))
    ap.add_argument('--doc', default=os.path.join(HERE, 'docs', 'fastsim.md'))
    ap.add_argument('--no-doc', action='store_true', help='print the tables only')
    ap.add_argument('--csv', default='', help='one line per point, rule and source')
    ap.add_argument('--work', default='', help='keep the runs in this folder (default: a temporary one)')
    ap.add_argument('--reuse', action='store_true', help='with --work: keep the runs found there (same namelist)')
    ap.add_argument('--patches', type=int, default=0, help='only the first N patches of each family')
    ap.add_argument('--lock', default='/tmp/kcreep-bench.lock', help="held around every kcreep run ('none': no lock)")
    ap.add_argument('--seed', type=int, default=30)
    args = ap.parse_args()
    args.kcreep = os.path.abspath(args.kcreep)
    sys.path.insert(0, os.path.join(HERE, 'python'))
    import numpy as np

    rng = random.Random(args.seed)
    patches = generate_patches(rng, args.patches or None)
    results = []
    t_start = time.time()
    with tempfile.TemporaryDirectory() as tmp:
        folder = os.path.abspath(args.work) if args.work else tmp
        os.makedirs(folder, exist_ok=True)
        for k, patch in enumerate(patches):
            res = run_patch(args, folder, patch)
            results.append(res)
            print(f'[{k + 1}/{len(patches)}] {res["name"]}: {res["n"]} cells, {res["seconds"]:.1f} s', flush=True)
    print(f'{time.time() - t_start:.0f} s wall, kcreep {CPU[0]:.0f} s CPU', flush=True)
    report(np, args, results, CPU[0])


def report(np, args, results, seconds):
    from kcreep.docsection import replace_section
    records = []   # (family, kind, patch, direction, level, rule, source, error)
    check = 0.0
    for res in results:
        roll = res['roll']
        mine = variants(np, res)
        errors = point_errors(res)
        for q, (creep, d, s) in enumerate(res['points']):
            fx_e, fy_e, fn = roll[q][3], roll[q][4], roll[q][6]
            kind = 'pure' if sum(1 for v in DIRECTIONS[d] if v) == 1 else 'combined'
            for rule in RULES:
                for src in SOURCES:
                    records.append((res['family'], kind, res['name'], d, s, rule, src, errors[(rule, src)][q]))
                fx, fy, _ = res['fast'][(rule, 'exact', q)]
                check = max(check, math.hypot(fx - mine[rule][0][q], fy - mine[rule][1][q]) / (MU * fn))
            for rule, (fx, fy, _) in mine.items():
                if rule in RULES:
                    continue
                records.append((res['family'], kind, res['name'], d, s, rule, 'exact',
                                math.hypot(fx[q] - fx_e, fy[q] - fy_e) / (MU * fn)))
    if args.csv:
        with open(args.csv, 'w') as f:
            f.write('family,kind,patch,direction,level,rule,source,error_mufn\n')
            for r in records:
                f.write(f'{r[0]},{r[1]},{r[2]},"{DIRECTIONS[r[3]]}",{r[4]},"{r[5]}",{r[6]},{r[7]:.6e}\n')
    text = tables(np, results, records, check, seconds)
    print(text)
    if not args.no_doc and not args.patches:
        replace_section(args.doc, 'fastsim_vs_exact', text)


def tables(np, results, records, check, seconds):
    """The Markdown of the doc section: kcreep's rules and sources, the variants, the patches."""
    combos = [(r, s) for r in RULES for s in SOURCES]
    variants_ = [('aligned', 'exact')] + sorted({(r[5], r[6]) for r in records} - set(combos))
    fams = ('ellipse', 'mask', 'gap')
    count = {f: sum(1 for r in results if r['family'] == f) for f in fams}
    npts = len(results[0]['points'])
    by = {}
    for r in records:
        by.setdefault((r[5], r[6]), []).append(r)

    def grid(cols, label):
        out = ['| patches | creepages | points | ' + ' | '.join(label(c) for c in cols) + ' |',
               '|' + '---|' * (3 + len(cols))]
        for fam in fams + ('all',):
            for kind in ('pure', 'combined', 'all'):
                cells, n = [], 0
                for c in cols:
                    e = np.array([r[7] for r in by[c] if (fam == 'all' or r[0] == fam) and
                                  (kind == 'all' or r[1] == kind)]) * 100
                    n = n or e.size
                    cells.append(f'{e.max():.1f} / {np.percentile(e, 95):.1f} / {np.median(e):.2f}' if e.size else '-')
                out.append(f'| {fam} | {kind} | {n} | ' + ' | '.join(cells) + ' |')
        return out

    lines = [f'Measured by `scripts/fastsim_vs_exact.py`: {len(results)} patches ({count["ellipse"]} ellipses, '
             f'{count["mask"]} masks, {count["gap"]} gaps; {min(r["n"] for r in results)}-'
             f'{max(r["n"] for r in results)} cells) x {npts} creepages = {len(results) * npts} points per rule and '
             f'L source; kcreep ran {seconds:.0f} s of CPU. Error of a point: |F - F_exact| / (mu Fn), F = (Fx, Fy), '
             f'in %; a cell: largest / 95th percentile / median over its points.', '',
             'kcreep\'s rules (`&fastsim rule`) with the three L sources (`flexibility`):', '']
    lines += grid(combos, lambda c: f'{c[0]}, L {c[1]}')
    lines += ['', 'Variants with the exact L (a numpy copy of kcreep\'s FASTSIM, which repeats kcreep\'s creep '
              f'tables within {check:.0e} of mu Fn, the digits of the maps\' pressure):', '']
    lines += grid(variants_, lambda c: c[0])
    # per patch: the largest error over its points (what the summary of a run with both groups prints)
    worst = {}
    for c, rs in by.items():
        for r in rs:
            worst[(c, r[2])] = max(worst.get((c, r[2]), 0), r[7])
    names = [r['name'] for r in results]
    best = {(r, 'exact'): 0 for r in RULES}
    for n in names:
        low = min(worst[(c, n)] for c in best)
        for c in best:
            best[c] += worst[(c, n)] <= low * (1 + 1e-9)     # ties (a pure creepage the worst point) count for each
    ties = sum(1 for n in names if sum(worst[(c, n)] <= min(worst[(b, n)] for b in best) * (1 + 1e-9)
                                         for c in best) > 1)
    lines += ['', 'Per patch, the largest error over its points (what the summary of a run with `&fastsim` and '
              '`&rolling` prints), % of mu Fn: median and largest over the patches; and on how many patches each of '
              f'kcreep\'s rules with the exact L has the smallest (ties, {ties} patches whose worst point is a pure '
              'creepage, count for each):', '',
              '| rule, L | median patch | worst patch | best on patches |', '|---|---|---|---|']
    for c in combos + variants_[1:]:
        have = [n for n in names if (c, n) in worst]
        w = np.array([worst[(c, n)] for n in have]) * 100
        lines.append(f'| {c[0]}, {c[1]} | {np.median(w):.2f} | {w.max():.1f} ({have[int(w.argmax())]}) | '
                     f'{best.get(c, "-")}{"" if len(have) == len(names) else f" ({len(have)} patches)"} |')
    lines += ['', 'The default against plain FASTSIM with the same (exact) L, point by point: excess = error of '
              '`aligned` less that of `weighted` (Kalker\'s single L) or `separate`, % of mu Fn; largest over the '
              'points, and how many patches and points exceed 3 %:', '',
              '| patches | largest excess over weighted | over separate | patches above 3 % (either) | '
              'points above 3 % (either) |', '|---|---|---|---|---|']
    al, wt, sp = (by[(r, 'exact')] for r in ('aligned', 'weighted', 'separate'))
    for fam in fams + ('all',):
        k = [i for i, r in enumerate(al) if fam == 'all' or r[0] == fam]
        ew = np.array([al[i][7] - wt[i][7] for i in k]) * 100
        es = np.array([al[i][7] - sp[i][7] for i in k]) * 100
        above = np.maximum(ew, es) > 3
        pats = {al[i][2] for i, a in zip(k, above) if a}
        lines.append(f'| {fam} | {ew.max():.1f} ({al[k[int(ew.argmax())]][2]}) | {es.max():.1f} '
                     f'({al[k[int(es.argmax())]][2]}) | {len(pats)} of {len({al[i][2] for i in k})} | '
                     f'{above.sum()} of {len(k)} |')
    return '\n'.join(lines) + '\n'


if __name__ == '__main__':
    main()
