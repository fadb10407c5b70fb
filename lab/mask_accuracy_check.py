#!/usr/bin/env python3
"""The shipped mask examples' verdict, estimate, true error and time against
references from much finer splits (the calibration of split_level_estimate
itself is the test calibration_split_levels, whose references this uses).

    lab/mask_accuracy_check.py --run [--target T] [--kcreep PATH]
        the shipped mask examples (input/*.nml) run as given with target_error T
        (default 1e-3), one thread, wall time per run; their errors against the
        references (run it under flock /tmp/kcreep-bench.lock for timing)

Levels: docs/data/mask_split_levels.dat ('name k cells C11 C22 C23 seconds',
lab/mask_split_levels.py: every cell split k x k, GMRES to 1e-9). The
reference of a mask: split_level_estimate through its levels with
k >= kmax / 2 (kmax 11-56, 120,000-330,000 cells), u its estimate, as
build/tests/test_split_levels prints them.
"""
import os
import re
import subprocess
import sys
import time

if any(a in ("-h", "--help") for a in sys.argv[1:]) or len(sys.argv) < 2:
    print(__doc__.strip())
    sys.exit(0)

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
LEVELS = os.path.join(REPO, "docs", "data", "mask_split_levels.dat")
COEFFS = ("C11", "C22", "C23")
CHECK = os.path.join(REPO, "build", "tests", "test_split_levels")


def references():
    """{name: [(f0, u) per coefficient]}: the references of the calibration test
    (tests/calibration/test_split_levels.f90, the library's split_level_estimate
    through each mask's levels with k >= kmax / 2), as it prints them."""
    out = subprocess.run([CHECK, LEVELS], capture_output=True, text=True).stdout
    refs = {}
    for line in out.splitlines():
        w = line.split()
        if w and w[0] == "reference":
            refs.setdefault(w[1], []).append((float(w[3]), float(w[4])))
    if not refs:
        sys.exit(f"mask_accuracy_check.py: no references from {CHECK} (build the tests first)")
    return refs


MASKS = ("kidney_inline", "two_patches", "crescent", "two_lobed", "rectangle", "superellipse", "twin")


def run(target, kcreep):
    refs = references()
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
    target = float(args[args.index("--target") + 1]) if "--target" in args else 1e-3
    kcreep = args[args.index("--kcreep") + 1] if "--kcreep" in args else os.path.join(REPO, "build", "kcreep")
    return run(target, kcreep)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
