#!/usr/bin/env python3
"""kcreep against CONTACT on CONTACT's own circle patch: the Hertzian circle of
radius 5 of ../shared/contact-samples (circle_r5_nu25.inp, full adhesion,
three cases xi, eta, phi) on finer grids. CONTACT runs the three cases
(OMP_NUM_THREADS=1); kcreep reads its .out and .mat (&patch shape =
'contact', target_error = 0, threads = 1) and solves all three load cases at
once. Prints, per grid: CONTACT's wall and CPU time; kcreep's whole run
(median wall and CPU of R runs) and the assemble + factor + solve time its
summary prints; the run over that time; CONTACT's time over kcreep's run,
wall and CPU (on a busy machine the CPU ratio is the steadier). Takes the
benchmark lock (/tmp/kcreep-bench.lock) itself. Standard library only.

    scripts/bench/bench_contact.py --contact CONTACT_BINARY [--kcreep PATH] [--grids 84,132] [--repeats R]
    scripts/bench/bench_contact.py --help

CONTACT_BINARY: CONTACT's contact_linux64 (../shared/contact-build/README.md).
"""
import fcntl
import os
import re
import statistics
import subprocess
import sys
import tempfile
import time

args = sys.argv[1:]
if any(a in ("-h", "--help") for a in args) or "--contact" not in args:
    print(__doc__.strip())
    sys.exit(0 if args else 2)


def option(name, default):
    return args[args.index(name) + 1] if name in args else default


root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
contact = os.path.abspath(option("--contact", ""))
kcreep = os.path.abspath(option("--kcreep", os.path.join(root, "build", "kcreep")))
grids = [int(g) for g in option("--grids", "84,132").split(",")]
repeats = int(option("--repeats", "5"))
sample = os.path.join(root, "..", "shared", "contact-samples", "circle_r5_nu25.inp")
span = 11.0          # the sample's potential contact: 2 x radius 5 x SCALE 1.1 (mm)


def run(command, cwd, env=None):
    """Wall and CPU (user + system) seconds of one run, and its output."""
    t0 = time.perf_counter()
    proc = subprocess.Popen(command, cwd=cwd, env=env, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL,
                            text=True)
    out = proc.stdout.read()
    _, status, usage = os.wait4(proc.pid, 0)
    wall = time.perf_counter() - t0
    if os.waitstatus_to_exitcode(status) != 0:
        sys.exit(f"bench_contact: {' '.join(command)} failed in {cwd}")
    return wall, usage.ru_utime + usage.ru_stime, out


lock = open("/tmp/kcreep-bench.lock", "w")
fcntl.flock(lock, fcntl.LOCK_EX)       # one benchmark at a time on a shared machine
work = tempfile.mkdtemp(prefix="kcreep-bench-contact-")
env1 = {**os.environ, "OMP_NUM_THREADS": "1"}
print("| grid | CONTACT, 3 cases: wall, CPU [s] | kcreep run: wall, CPU [s] | kcreep printed "
      "assemble+factor+solve [s] | run / printed (wall) | CONTACT / kcreep: wall, CPU |")
print("|---|---|---|---|---|---|")
for m in grids:
    text = open(sample).read()
    text = re.sub(r"^ +33 +33 ", f"   {m}   {m} ", text, flags=re.M)
    text = text.replace("0.3333333333333333", repr(span / m))         # DQ = DX
    with open(os.path.join(work, f"circle{m}.inp"), "w") as f:
        f.write(text)
    contact_wall, contact_cpu, _ = run([contact, "2", f"circle{m}"], work, env1)
    with open(os.path.join(work, f"c{m}.nml"), "w") as f:
        f.write(f"&patch shape = 'contact', contact_file = 'circle{m}.out', contact_case = 1 /\n"
                "&solver target_error = 0, threads = 1 /\n")
    run([kcreep, f"c{m}.nml"], work, env1)                           # warm-up (page cache)
    walls, cpus, printed = [], [], []
    for _ in range(repeats):
        wall, cpu, out = run([kcreep, f"c{m}.nml"], work, env1)
        times = re.search(r"time assemble factor solve total \[s\]: +(\S+) +(\S+) +(\S+) +(\S+)", out)
        walls.append(wall)
        cpus.append(cpu)
        printed.append(float(times.group(4)))
    w, c, p = statistics.median(walls), statistics.median(cpus), statistics.median(printed)
    print(f"| {m} x {m} | {contact_wall:.2f}, {contact_cpu:.2f} | {w:.3f}, {c:.3f} | {p:.3f} | {w / p:.2f} | "
          f"{contact_wall / w:.0f}, {contact_cpu / c:.0f} |")
print(f"(median of {repeats} kcreep runs, one CONTACT run; load average at the end "
      f"{' '.join(open('/proc/loadavg').read().split()[:3])})")
