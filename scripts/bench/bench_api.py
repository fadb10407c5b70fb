#!/usr/bin/env python3
"""Body of scripts/bench/bench_api.sh (needs numpy: /usr/bin/python3).

    scripts/bench/bench_api.py BUILD_DIR REPOSITORY_ROOT [ARGS]   (scripts/bench/bench_api.sh calls it)
    scripts/bench/bench_api.py --help                            this text
"""
import os
import statistics
import subprocess
import sys
import tempfile
import time
if any(a in ("-h", "--help") for a in sys.argv[1:]):
    print(__doc__.strip())
    sys.exit(0)

build, root = sys.argv[1], sys.argv[2]
args = sys.argv[3:]
repeats = int(args[args.index("--repeats") + 1]) if "--repeats" in args else 50
write_docs = "--no-docs" not in args
sys.path.insert(0, os.path.join(root, "python"))
import numpy as np  # noqa: E402
import kcreep  # noqa: E402
from kcreep import docsection  # noqa: E402

example = os.path.join(build, "tests", "kcreep_api_example")
kcreep_exe = os.path.join(build, "kcreep")
m = 40
y, x = np.mgrid[0:m, 0:m]
inside = ((-1 + (x + 0.5) * 2 / m) ** 2 + (-1 + (y + 0.5) * 2 / m) ** 2) <= 1


def c_api(shape, estimate=False):
    args = [example, "bench", str(repeats), shape, "auto"] + (["estimate"] if estimate else [])
    out = subprocess.run(args, capture_output=True, text=True, check=True).stdout
    words = out.split()
    return float(words[words.index("first_ms") + 1]), float(words[words.index("repeated_median_ms") + 1])


def moving_mask(step):
    # the C program's time-stepping loop: semi-axes breathing, centre drifting
    a, b, xc = 0.9 + 0.05 * np.sin(0.7 * step), 0.9 + 0.05 * np.cos(0.5 * step), 0.03 * np.sin(0.3 * step)
    return ((-1 + (x + 0.5) * 2 / m - xc) / a) ** 2 + ((-1 + (y + 0.5) * 2 / m) / b) ** 2 <= 1


def python(shape):
    times = []
    solver = kcreep.Solver(nu=0.25, g=1.0, target_error=0.0, refine_grid=False, estimate_error=False)
    for step in range(repeats):
        t0 = time.perf_counter()
        if shape == "ellipse":
            r = solver.solve_ellipse(1.0, 1.0, m, m)
        elif shape == "moving":
            r = solver.solve_mask(moving_mask(step), 2 / m, 2 / m, -1 + 1 / m, -1 + 1 / m)
        else:
            r = solver.solve_mask(inside, 2 / m, 2 / m, -1 + 1 / m, -1 + 1 / m)
        r.c
        times.append(1e3 * (time.perf_counter() - t0))
    return times[0], statistics.median(times[1:])


def cli(shape):
    folder = tempfile.mkdtemp(prefix="kcreep-bench-api-")
    nml = os.path.join(folder, "case.nml")
    with open(nml, "w") as f:
        if shape == "ellipse":
            f.write(f"&patch mx = {m}, my = {m} /\n")
        else:
            rows = ", ".join("'" + "".join("1" if v else "0" for v in row) + "'" for row in inside)
            f.write(f"&patch shape = 'mask', dx = {2 / m}, dy = {2 / m}, x0 = {-1 + 1 / m}, y0 = {-1 + 1 / m}, "
                    f"mask_rows = {rows} /\n")
    times = []
    for _ in range(max(5, repeats // 5)):
        t0 = time.perf_counter()
        subprocess.run([kcreep_exe, nml], cwd=folder, capture_output=True, check=True)
        times.append(1e3 * (time.perf_counter() - t0))
    return times[0], statistics.median(times)


load_start = os.getloadavg()[0]
rows = []
for shape in ("ellipse", "mask", "moving"):
    c_first, c_rep = c_api(shape)
    _, c_rep_estimate = c_api(shape, estimate=True)
    p_first, p_rep = python(shape)
    _, cli_med = cli("mask" if shape == "moving" else shape)
    rows.append((shape, c_first, c_rep, c_rep_estimate, p_first, p_rep, cli_med))
load_end = os.getloadavg()[0]

lines = ["## Library calls: the in-loop cost (scripts/bench/bench_api.sh)", "",
         f"A {m} x {m} unit circle (ellipse shape, and the same cells as a mask), nu = 0.25, the library's "
         f"defaults (backward scheme, method auto, the grid as given) with the per-call error estimate off "
         f"(kcreep_set_error_control(h, 0, 0, 0): the grid is judged once, outside the loop; the column "
         f"'C, estimate on' keeps it: one more solve on the grid with twice the cell size (ellipse) or every "
         f"cell split 2 x 2 (mask)). The command line runs its default, error control. Times in ms: the first call on a new handle, then the median of "
         f"{repeats - 1} repeated calls on the same handle; the command line is the median wall time of whole "
         f"processes (start-up, namelist, table file). 'moving' is a time-stepping loop: a new mask every call "
         f"(semi-axes breathing by up to 5 %, centre drifting) on the same grid. Repeated calls reuse the "
         f"operator table and start GMRES from the last solution on the grid (an unchanged patch then "
         f"converges at once, to the same tolerance). Load average {load_start:.1f} at the start, {load_end:.1f} at "
         f"the end of the run.", "",
         "| patch | C first | C repeated | C repeated, estimate on | Python first | Python repeated | Python / C "
         "| CLI process |",
         "|---|---|---|---|---|---|---|---|"]
for shape, c_first, c_rep, c_rep_estimate, p_first, p_rep, cli_med in rows:
    lines.append(f"| {m} x {m} {shape} | {c_first:.2f} | **{c_rep:.2f}** | {c_rep_estimate:.2f} | {p_first:.2f} | "
                 f"{p_rep:.2f} | {p_rep / c_rep:.2f}x | {cli_med:.1f} |")
text = "\n".join(lines) + "\n"
print(text)
if write_docs:
    docsection.replace_section(os.path.join(root, "docs", "performance.md"), "api", text)
