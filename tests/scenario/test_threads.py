"""How many threads kcreep runs on (src/core/kcreep_threads.f90): an explicit
&solver threads is used as given; the automatic count (threads = 0) is one
thread for a patch too small for threads to pay, one beside as many busy
processes as the machine has CPUs, and never more than SLURM_CPUS_PER_TASK
or OMP_NUM_THREADS allow; the summary says how many ran. Bad values are
refused with a one-line error naming the variable and the allowed range.

What could fail: a threshold or load reading that lets a team form on a busy
machine (the collapse of issue 28), a knob that is ignored, a summary that
does not say."""
import os
import re
import subprocess
import time
import kctest as kc

folder = kc.setup()
big = "shape='ellipse', semi_a=1, semi_b=1, mx=200, my=200"      # 31,428 cells: threads pay (performance.md)
small = "shape='ellipse', semi_a=1, semi_b=1, mx=40, my=40"      # 1,264 cells: they do not


def threads_ran(patch, solver="method='iterative'", name="case", env=None):
    text = kc.namelist(patch, "nu=0.25", solver)
    with open(os.path.join(folder, name + ".nml"), "w") as f:
        f.write(text)
    proc = subprocess.run([kc.KCREEP, name + ".nml"], cwd=folder, capture_output=True, text=True,
                          env={**os.environ, **(env or {})})
    kc.check(proc.returncode == 0, f"{name}: exit status 0 ({proc.stderr.strip()[:200]})")
    m = re.search(r"^  threads: (\d+) \((.*)\)$", proc.stdout, re.M)
    kc.check(m is not None, f"{name}: the summary has a threads line")
    return (int(m.group(1)), m.group(2)) if m else (None, "")


clean = {k: v for k, v in os.environ.items() if k not in ("OMP_NUM_THREADS", "SLURM_CPUS_PER_TASK")}
os.environ.clear()
os.environ.update(clean)

n, why = threads_ran(big, "method='iterative', threads=3", "explicit")
kc.check(n == 3 and "&solver threads" in why, f"threads = 3 runs 3 and says it was asked for (got {n}: {why})")
n, why = threads_ran(small, "method='iterative'", "small")
kc.check(n == 1 and why.startswith("automatic"), f"automatic on 1,264 cells: 1 thread (got {n}: {why})")
n, _ = threads_ran(big, "method='iterative'", "slurm", {"SLURM_CPUS_PER_TASK": "1"})
kc.check(n == 1, f"SLURM_CPUS_PER_TASK=1 caps the automatic count at 1 (got {n})")
n, _ = threads_ran(big, "method='iterative'", "omp", {"OMP_NUM_THREADS": "1", "SLURM_CPUS_PER_TASK": "2"})
kc.check(n == 1, f"OMP_NUM_THREADS=1 caps it at 1 and wins over SLURM_CPUS_PER_TASK (got {n})")

# beside one busy process per CPU the automatic count must be one thread
busy = [subprocess.Popen(["sh", "-c", "while :; do :; done"]) for _ in range(os.cpu_count() or 1)]
try:
    time.sleep(0.5)
    seen = [threads_ran(big, "method='iterative'", f"loaded{k}")[0] for k in range(3)]
finally:
    for p in busy:
        p.kill()
        p.wait()
kc.check(seen == [1, 1, 1], f"beside {len(busy)} busy processes the automatic count is 1 (got {seen})")

for value in ("-1", "1025"):
    code, _, err, _ = kc.run(kc.namelist(small, "", f"threads={value}"), folder, "bad", expect_ok=False)
    kc.check(code == 2 and "&solver threads = " + value in err and "allowed: 0 = automatic, or 1 to 1024" in err
             and len(err.strip().splitlines()) == 1,
             f"threads = {value} refused in one line naming the range ({err.strip()})")
kc.finish()
