#!/usr/bin/env python3
"""Benchmark of creep forces inside a multibody time step (issue 48), one thread.

  scripts/bench_loop.py [--steps 200] [--points 10000] [--repeat 3] [--doc docs/performance.md]
  scripts/bench_loop.py --builds [--vs OTHER_SOURCE_DIR] [--repeat 3]

On the 20 x 20-cell Hertzian circle (316 cells, Fn = 1, mu = 0.3) along a
slowly varying creepage history of --steps steps (xi = 2e-3 sin 3t,
eta = 1e-3 cos 2t, phi = 0.2 sin t, t in [0, 1]), through the Python package,
CPU time of this process (time.process_time), best of --repeat:
  - Solver.rolling (exact), one call per step: the handle keeps the solver and
    the last solutions (warm starts across calls);
  - Solver.rolling, all steps in one call;
  - Solver.fast_forces: its build (the first call on the patch), then one call
    per step, and --points random creepages in one call;
  - Solver.fastsim (rule 'aligned'), all steps in one call;
  - CONTACT's 17 ms per point at this grid size (the issue's figure, not run).
The distance from the exact forces, max |F - F_exact| / (mu Fn) with
F = (Fx, Fy), is taken along the history. Holds /tmp/kcreep-bench.lock (one
benchmark at a time on the machine); with --doc, writes the table into the
section `loop-bench` of that page. Needs numpy.

--builds: the fast model's build time on the Hertzian circle on 20 x 20
cells (316), the ellipses a/b = 5 (400) and 1.5 (840), the L-shaped mask on
24 x 24 (432) and 36 x 36 (972) cells (the ellipses are their own mirror
images in y, which halves their build; the L-shapes are not), and rolling
one call per step along the history above, for this repository's build and,
with --vs, another source tree's build beside it (each in a process of its
own, in turn, --repeat times; medians and the ratio new / old).
"""
import argparse
import fcntl
import json
import os
import statistics
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def ellipse(np, a, b, cells_a):
    """A Hertzian ellipse (semi-axes a, b) on square cells, cells_a across 2a: inside,
    its pressure for Fn = 1, the cell size and the grid's first cell centres."""
    d = 2 * a / cells_a
    ny = max(2, int(round(2 * b / d)))
    x = (np.arange(cells_a) + 0.5) * d - a
    y = (np.arange(ny) + 0.5) * d - ny * d / 2
    X, Y = np.meshgrid(x, y)
    r2 = (X / a) ** 2 + (Y / b) ** 2
    return normalised(np, r2 < 1, np.sqrt(np.clip(1 - r2, 0, None)), d, x[0], y[0])


def l_shape(np, m):
    """The L-shaped mask on m x m cells of [-1, 1]^2 (three quarters), pressure as ellipse's."""
    x = (np.arange(m) + 0.5) / m * 2 - 1
    X, Y = np.meshgrid(x, x)
    p = np.sqrt(np.clip(1 - X ** 2, 0, None) * np.clip(1 - Y ** 2, 0, None))
    return normalised(np, (X < 0) | (Y < 0), p, 2.0 / m, x[0], x[0])


def normalised(np, inside, p, d, x0, y0):
    p = np.where(inside, p, 0.0)
    return inside, p / (p.sum() * d * d), d, x0, y0


def history(np, steps):
    """The slowly varying creepage history (xi, eta, phi) of the time step."""
    t = np.linspace(0, 1, steps)
    return np.c_[2e-3 * np.sin(3 * t), 1e-3 * np.cos(2 * t), 0.2 * np.sin(t)]


def best(f, repeat):
    times = []
    for _ in range(repeat):
        t0 = time.process_time()
        out = f()
        times.append(time.process_time() - t0)
    return min(times), out


def measure_builds(root):
    """--measure-builds ROOT: the --builds figures of ROOT's build (run in a process of
    its own, so that it loads ROOT's libkcreep.so), printed as one JSON line."""
    os.environ["OMP_NUM_THREADS"] = "1"
    sys.path.insert(0, os.path.join(root, "python"))
    import numpy as np
    import kcreep
    out = {}
    cases = [("circle", ellipse(np, 1, 1, 20)), ("a/b = 5", ellipse(np, 1, 0.2, 50)),
             ("a/b = 1.5", ellipse(np, 1.5, 1, 40)), ("L 24", l_shape(np, 24)), ("L 36", l_shape(np, 36))]
    for name, (inside, p, d, x0, y0) in cases:
        s = kcreep.Solver(threads=1, refine_grid=False, estimate_error=False, target_error=0)
        r = s.solve_mask(inside, d, d, x0, y0)
        t0 = time.process_time()
        s.fast_forces(0.3, [[1e-3, 0, 0]], p)
        out[f"build, {name} ({r.n} cells) [s]"] = time.process_time() - t0
    inside, p, d, x0, y0 = cases[0][1]
    steps = history(np, 200)
    s = kcreep.Solver(threads=1, refine_grid=False, estimate_error=False, target_error=0)
    s.solve_mask(inside, d, d, x0, y0)
    s.rolling(0.3, steps[:1], p)
    t0 = time.process_time()
    for c in steps:
        s.rolling(0.3, [c], p)
    out["rolling one call per step, circle [ms]"] = (time.process_time() - t0) / len(steps) * 1e3
    print(json.dumps(out))


def measure(root):
    run = subprocess.run([sys.executable, os.path.abspath(__file__), "--measure-builds", root],
                         capture_output=True, text=True)
    if run.returncode != 0:
        sys.exit(f"bench_loop: the run on {root} failed: {run.stderr.strip().splitlines()[-1:]}")
    return json.loads(run.stdout.strip().splitlines()[-1])


def build_times(args):
    """--builds: the build times side by side (see the docstring)."""
    roots = [HERE] + ([os.path.abspath(args.vs)] if args.vs else [])
    for root in roots:
        if not os.path.exists(os.path.join(root, "build", "libkcreep.so")):
            sys.exit(f"bench_loop: no build/libkcreep.so in {root} (build it: scripts/setup.sh)")
    runs = {root: [] for root in roots}
    with open("/tmp/kcreep-bench.lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        for _ in range(args.repeat):
            for root in roots:
                runs[root].append(measure(root))
    print(f"one thread, CPU time, medians of {args.repeat}" + (f"; old: {roots[1]}" if args.vs else ""))
    for k in runs[HERE][0]:
        new = statistics.median(r[k] for r in runs[HERE])
        if args.vs:
            old = statistics.median(r[k] for r in runs[roots[1]])
            print(f"  {k:48s} new {new:7.3f}  old {old:7.3f}  new/old {new / old:5.2f}")
        else:
            print(f"  {k:48s} {new:7.3f}")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0], formatter_class=argparse.RawDescriptionHelpFormatter,
                                 epilog=__doc__)
    ap.add_argument("--steps", type=int, default=200)
    ap.add_argument("--points", type=int, default=10000)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--doc", default=None)
    ap.add_argument("--builds", action="store_true", help="the fast model's build times (and rolling warm) instead")
    ap.add_argument("--vs", default=None, help="with --builds: another source tree with a build, beside this one")
    ap.add_argument("--measure-builds", default=None, help=argparse.SUPPRESS)
    args = ap.parse_args()
    if args.measure_builds:
        measure_builds(args.measure_builds)
        return
    if args.builds:
        build_times(args)
        return
    os.environ["OMP_NUM_THREADS"] = "1"
    sys.path.insert(0, os.path.join(HERE, "python"))
    import numpy as np
    import kcreep
    from kcreep.docsection import replace_section
    mu, n = 0.3, args.steps
    inside, p, d, x0, y0 = ellipse(np, 1, 1, 20)
    steps = history(np, n)
    rng = np.random.default_rng(1)
    random = rng.normal(size=(args.points, 3)) * [2e-3, 2e-3, 0.2]

    def solver():
        s = kcreep.Solver(threads=1, refine_grid=False, estimate_error=False, target_error=0)
        s.solve_mask(inside, d, d, x0, y0)
        return s

    with open("/tmp/kcreep-bench.lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        s = solver()
        exact, _ = s.rolling(mu, steps, p)
        t_batch, _ = best(lambda: s.rolling(mu, steps, p), args.repeat)
        t_single, single = best(lambda: np.array([s.rolling(mu, [c], p)[0][0] for c in steps]), args.repeat)
        builds = []
        for _ in range(args.repeat):
            f = solver()
            t0 = time.process_time()
            f.fast_forces(mu, steps[:1], p)
            builds.append(time.process_time() - t0)
        t_fast_single, fast = best(lambda: np.array([f.fast_forces(mu, [c], p)[0] for c in steps]), args.repeat)
        t_fast_many, _ = best(lambda: f.fast_forces(mu, random, p), args.repeat)
        t_fastsim, (fsim, _) = best(lambda: s.fastsim(mu, steps, p), args.repeat)

    def distance(forces):
        return 100 * np.hypot(*(forces - exact)[:, :2].T).max() / mu

    rows = [
        ("`Solver.rolling` (exact), one call per step (warm starts across calls)", f"{1e3 * t_single / n:.2f} ms",
         f"{distance(single):.1e} %"),
        ("`Solver.rolling` (exact), all steps in one call", f"{1e3 * t_batch / n:.2f} ms", "0"),
        ("`Solver.fast_forces`, one call per step", f"{1e6 * t_fast_single / n:.1f} us", f"{distance(fast):.3f} %"),
        (f"`Solver.fast_forces`, {args.points} random points in one call",
         f"{1e6 * t_fast_many / args.points:.2f} us ({t_fast_many:.3f} s)", ""),
        ("`Solver.fast_forces`, its build on the patch (first call)", f"{min(builds):.2f} s", ""),
        ("`Solver.fastsim` (rule 'aligned'), all steps in one call", f"{1e6 * t_fastsim / n:.1f} us",
         f"{distance(fsim):.2f} %"),
        ("CONTACT (reference, the issue's figure)", "17 ms", "0"),
    ]
    text = [f"Measured by `scripts/bench_loop.py` (20 x 20-cell Hertzian circle, 316 cells, mu = 0.3, "
            f"{n}-step slowly varying creepage history, Python, one thread, CPU time, best of {args.repeat}; "
            f"distance: largest |F - F_exact| / (mu Fn) along the history):", "",
            "| way | time per point | distance from exact |", "|---|---|---|"]
    text += [f"| {a} | {b} | {c} |" for a, b, c in rows]
    out = "\n".join(text)
    print(out)
    if args.doc:
        replace_section(args.doc, "loop-bench", out)


if __name__ == "__main__":
    main()
