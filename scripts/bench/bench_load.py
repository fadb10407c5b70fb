#!/usr/bin/env python3
"""Body of scripts/bench/bench_load.sh: kcreep's runs alone and beside N busy
processes (N = the CPUs of this machine), each with the default thread count
and with OMP_NUM_THREADS=1, in turns (default, one thread, default, ...), the
median wall time of each. Standard library only (any python3).

    scripts/bench/bench_load.py BUILD_DIR REPOSITORY_ROOT [--repeats R] [--no-docs] [--only TEXT]
    scripts/bench/bench_load.py --help

--only TEXT runs the runs whose label contains TEXT, and writes no docs.
"""
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

if any(a in ("-h", "--help") for a in sys.argv[1:]) or len(sys.argv) < 3:
    print(__doc__.strip())
    sys.exit(0)

build, root = sys.argv[1], sys.argv[2]
args = sys.argv[3:]
repeats = int(args[args.index("--repeats") + 1]) if "--repeats" in args else 5
only = args[args.index("--only") + 1] if "--only" in args else ""
write_docs = "--no-docs" not in args and not only
kcreep = os.path.join(build, "kcreep")
cpus = os.cpu_count() or 1

work = tempfile.mkdtemp(prefix="kcreep-bench-load-")
shutil.copytree(os.path.join(root, "input"), os.path.join(work, "input"))
with open(os.path.join(work, "ellipse_6x4.nml"), "w") as f:   # the README's example
    f.write("&patch    shape = 'ellipse', semi_a = 6, semi_b = 4, mx = 60, my = 40 /\n"
            "&material g = 82000, nu = 0.28 /\n&solver   scheme = 'backward' /\n")
for m in (128, 280):
    with open(os.path.join(work, f"circle_{m}.nml"), "w") as f:
        f.write(f"&patch shape = 'ellipse', semi_a = 1, semi_b = 1, mx = {m}, my = {m} /\n"
                "&material nu = 0.25 /\n&solver method = 'iterative', target_error = 0 /\n")
# the S1002 table of input/s1002_uic60.nml on 3 shifts with exact rolling on every patch
profiles = os.path.abspath(os.path.join(root, "..", "shared", "profiles"))
with open(os.path.join(work, "s1002_rolling.nml"), "w") as f:
    f.write(f"&wheel_rail wheel_file = '{profiles}/MBench_S1002_v3.prw', rail_file = '{profiles}/MBench_UIC60_v3.prr',\n"
            "  shift_from = 0, shift_to = 4, shift_step = 2, vertical_force = 80000 /\n"
            "&material g = 82000, nu = 0.28 /\n&rolling mu = 0.3, creepages = 0 0 0, 2e-3 0 0 /\n")
os.makedirs(os.path.join(work, "batch"))
with open(os.path.join(work, "batch20.list"), "w") as listing:
    for k in range(20):   # ellipses a/b 0.3 to 3.2, nu 0 to 0.475, the default run (error control)
        name = os.path.join(work, "batch", f"e{k:02d}.nml")
        with open(name, "w") as f:
            f.write(f"&patch shape = 'ellipse', semi_a = {0.3 + 0.15 * k:.2f}, semi_b = 1 /\n"
                    f"&material nu = {0.025 * k:.3f} /\n")
        listing.write(name + "\n")

cases = [
    ("README example (ellipse_6x4.nml)", [kcreep, "ellipse_6x4.nml"]),
    ("input/crescent.nml", [kcreep, "input/crescent.nml"]),
    ("input/wheel_rail_fastsim.nml", [kcreep, "input/wheel_rail_fastsim.nml"]),
    ("128 x 128 circle, iterative, target_error = 0", [kcreep, "circle_128.nml"]),
    ("280 x 280 circle, iterative, target_error = 0", [kcreep, "circle_280.nml"]),
    ("--batch of 20 ellipses", [kcreep, "--batch", "batch20.list"]),
    ("input/wheel_rail_rolling.nml (&rolling, 30 points)", [kcreep, "input/wheel_rail_rolling.nml"]),
    ("S1002/UIC60 table, 3 shifts, &rolling", [kcreep, "s1002_rolling.nml"]),
]
cases = [c for c in cases if only in c[0]]


def timed(command, one_thread):
    env = dict(os.environ)
    env.pop("OMP_NUM_THREADS", None)
    if one_thread:
        env["OMP_NUM_THREADS"] = "1"
    t0 = time.perf_counter()
    subprocess.run(command, cwd=work, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=True)
    return time.perf_counter() - t0


def measure():
    rows = []
    for label, command in cases:
        timed(command, False)   # warm-up (page cache)
        default, single = [], []
        for _ in range(repeats):
            default.append(timed(command, False))
            single.append(timed(command, True))
        ratios = [d / s for d, s in zip(default, single)]
        rows.append((label, statistics.median(default), statistics.median(single), statistics.median(ratios),
                     max(ratios)))
    return rows


alone = measure()
hogs = [subprocess.Popen(["sh", "-c", "while :; do :; done"]) for _ in range(cpus)]
try:
    time.sleep(1)
    loaded = measure()
finally:
    for h in hogs:
        h.kill()
        h.wait()
shutil.rmtree(work, ignore_errors=True)

lines = ["## Threads on a busy machine (scripts/bench/bench_load.sh)", "",
         f"Each run alone and beside {cpus} busy processes (one per CPU of this {cpus}-CPU machine), with "
         f"the default thread count (automatic) and with OMP_NUM_THREADS=1, in turns; wall time of the whole "
         f"process, median of {repeats} pairs, in seconds; 'ratio' is the median over the pairs of "
         f"default / one thread, 'worst' its largest pair. Done when every loaded ratio is at most 1.3 and no "
         f"idle ratio above 1 beyond the noise.", ""]
lines += ["| run | alone: default | alone: 1 thread | alone: ratio (worst) | loaded: default | loaded: 1 thread "
          "| loaded: ratio (worst) |", "|---|---|---|---|---|---|---|"]
for a, b in zip(alone, loaded):
    lines.append(f"| {a[0]} | {a[1]:.3f} | {a[2]:.3f} | {a[3]:.2f} ({a[4]:.2f}) | {b[1]:.3f} | {b[2]:.3f} | "
                 f"{b[3]:.2f} ({b[4]:.2f}) |")
text = "\n".join(lines) + "\n"
print(text)
if write_docs:
    sys.path.insert(0, os.path.join(root, "python"))
    from kcreep import docsection  # noqa: E402  (standard library only)
    docsection.replace_section(os.path.join(root, "docs", "performance.md"), "load", text)
