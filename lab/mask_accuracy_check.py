#!/usr/bin/env python3
"""The refinement engine on split patches (masks) against references from
much finer splits: the calibration of split_level_estimate and the shipped
mask examples' verdict, estimate, true error and time.

    lab/mask_accuracy_check.py --calibrate [--levels FILE]
        the estimator (constants read from src/refine/kcreep_refine_constants.f90)
        on every window of levels coarser than the reference's; exit 1 unless
        every case is bounded (allowing the reference's u) and the median
        estimate / error is at most 3.5 (about 3) for the engine's own fit width
    lab/mask_accuracy_check.py --run [--target T] [--kcreep PATH]
        the shipped mask examples (input/*.nml) run as given with target_error T
        (default 1e-3), one thread, wall time per run; their errors against the
        references (run it under flock /tmp/kcreep-bench.lock for timing)

Levels: docs/data/mask_split_levels.dat ('name k cells C11 C22 C23 seconds',
lab/mask_split_levels.py: every cell split k x k, GMRES to 1e-9). The
reference of a mask: the fit f0 + K h + L h^1.5 through its levels with
k >= kmax / 2 (kmax 11-56, 120,000-330,000 cells), u = the change of f0 for
p = 4/3 or 2 plus t95 x its standard error. Needs numpy.
"""
import os
import re
import subprocess
import sys
import time

if any(a in ("-h", "--help") for a in sys.argv[1:]) or len(sys.argv) < 2:
    print(__doc__.strip())
    sys.exit(0)
import numpy as np  # noqa: E402

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
LEVELS = os.path.join(REPO, "docs", "data", "mask_split_levels.dat")
CONSTANTS = os.path.join(REPO, "src", "refine", "kcreep_refine_constants.f90")
T95 = (12.706, 4.303, 3.182, 2.776, 2.571, 2.447, 2.365, 2.306, 2.262, 2.228)
COEFFS = ("C11", "C22", "C23")


def t95(dof):
    return T95[dof - 1] if dof <= len(T95) else 1.96 + 2.5 / dof


def constants():
    """split_min_levels, split_fit_width, split_order, split_order_range from the Fortran source."""
    text = open(CONSTANTS).read()
    ints = dict(re.findall(r"(split_min_levels|split_fit_width) = (\d+)", text))
    order = float(re.search(r"split_order = ([\d.]+)_real64", text).group(1))
    rng = re.search(r"split_order_range\(2\) = \[([^\]]+)\]", text).group(1)
    orders = [eval(x.replace("_real64", "")) for x in rng.split(",")]
    return int(ints["split_min_levels"]), int(ints["split_fit_width"]), order, orders


def fit(h, f, p):
    a = np.column_stack([np.ones_like(h), h, h ** p])
    c = np.linalg.lstsq(a, f, rcond=None)[0]
    n, k = a.shape
    se = np.nan
    if n > k:
        r = f - a @ c
        se = np.sqrt(r @ r / (n - k) * np.linalg.inv(a.T @ a)[0, 0])
    return c[0], se


def estimate(h, f, order, orders):
    """kcreep_refine_estimate split_level_estimate: (limit, relative estimate)."""
    limit, se = fit(h, f, order)
    spread = max(abs(fit(h, f, p)[0] - limit) for p in orders)
    return limit, (spread + (t95(len(h) - 3) * se if len(h) > 3 else 0)) / abs(limit)


def load(path=LEVELS):
    data = {}
    for line in open(path):
        w = line.split()
        data.setdefault(w[0], {})[int(w[1])] = np.array([float(x) for x in w[3:6]])
    return data


def references(data, order, orders):
    """{name: [(f0, u) per coefficient]}, and the coarsest k each reference uses."""
    refs, first = {}, {}
    for name, levels in data.items():
        ks = [k for k in sorted(levels) if k >= max(levels) / 2]
        first[name] = ks[0]
        h = np.array([1.0 / k for k in ks])
        refs[name] = []
        for j in range(3):
            f = np.array([levels[k][j] for k in ks])
            f0, rel = estimate(h, f, order, orders)
            refs[name].append((f0, rel * abs(f0)))
    return refs, first


def calibrate(path):
    kmin, width, order, orders = constants()
    data = load(path)
    refs, first = references(data, order, orders)
    ok = True
    for w in sorted({kmin, width}):
        ratios, bounded, bounded_u, cases = [], 0, 0, 0
        for name, levels in data.items():
            ks = sorted(levels)
            for top in ks:
                window = [k for k in ks if k <= top][-w:]
                if len(window) < w or top >= first[name] or window != list(range(window[0], top + 1)):
                    continue
                h = np.array([1.0 / k for k in window])
                for j in range(3):
                    f0, u = refs[name][j]
                    limit, rel = estimate(h, np.array([levels[k][j] for k in window]), order, orders)
                    err = abs(limit / f0 - 1)
                    cases += 1
                    bounded += rel >= err
                    bounded_u += rel + u / abs(f0) >= err
                    ratios.append(rel / max(err, 1e-12))
        median = float(np.median(ratios))
        print(f"fit width {w}: {cases} cases (splits coarser than the references'), bounded {bounded}, "
              f"allowing u {bounded_u}, median estimate / error {median:.2f}")
        ok = ok and bounded_u == cases and (w != width or median <= 3.5)
    print("calibration", "holds" if ok else "FAILS", f"(split_min_levels {kmin}, split_fit_width {width}, "
          f"split_order {order:g}, split_order_range {orders})")
    return 0 if ok else 1


MASKS = ("kidney_inline", "two_patches", "crescent", "two_lobed", "rectangle", "superellipse", "twin")


def run(target, kcreep):
    _, _, order, orders = constants()
    refs, _ = references(load(), order, orders)
    import tempfile
    import shutil
    folder = tempfile.mkdtemp(prefix="kcreep-mask-check-")
    shutil.copytree(os.path.join(REPO, "input"), os.path.join(folder, "input"))
    sys.path.insert(0, os.path.join(REPO, "python"))
    from kcreep import table
    print(f"| example (target {target:g}) | verdict | estimate C11 / C22 / C23 % | error against the reference % | "
          f"reference u % | finest cells | wall s |")
    print("|---|---|---|---|---|---|---|")
    for name in MASKS:
        text = open(os.path.join(folder, "input", name + ".nml")).read()
        text = re.sub(r"&fastsim.*?/", "", text, flags=re.S)   # the coefficients only
        text = text.replace("scheme = 'backward'", f"scheme = 'backward', target_error = {target:g}")
        text = re.sub(r"&output.*?/", "", text, flags=re.S) + "&output table_file = 'check.tab' /\n"
        path = os.path.join(folder, "input", "check.nml")
        open(path, "w").write(text)
        env = dict(os.environ, OMP_NUM_THREADS="1")
        t0 = time.time()
        subprocess.run([kcreep, "check.nml"], cwd=os.path.join(folder, "input"), env=env, check=True,
                       capture_output=True)
        wall = time.time() - t0
        row = table.read(os.path.join(folder, "input", "check.tab"))[0]
        c = [row["c11"], row["c22"], row["c23"]]
        est = [row["err11"], row["err22"], row["err23"]]
        err = [abs(c[j] / refs[name][j][0] - 1) for j in range(3)]
        u = [refs[name][j][1] / refs[name][j][0] for j in range(3)]
        print(f"| {name} | {row['verdict']} | {' / '.join(f'{100 * e:.4f}' for e in est)} | "
              f"{' / '.join(f'{100 * e:.4f}' for e in err)} | {' / '.join(f'{100 * x:.4f}' for x in u)} | "
              f"{int(row['n'])} | {wall:.2f} |")
    shutil.rmtree(folder, ignore_errors=True)
    return 0


def main(args):
    path = args[args.index("--levels") + 1] if "--levels" in args else LEVELS
    if "--calibrate" in args:
        return calibrate(path)
    target = float(args[args.index("--target") + 1]) if "--target" in args else 1e-3
    kcreep = args[args.index("--kcreep") + 1] if "--kcreep" in args else os.path.join(REPO, "build", "kcreep")
    return run(target, kcreep)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
