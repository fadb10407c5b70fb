"""The cluster scripts against a real SLURM: start a one-node cluster of this
machine in a private folder (scripts/slurm/local_cluster.sh), submit a small
sweep as a job array (scripts/slurm/run_cases_slurm.sh), kill one array task
on purpose, check that the gather step names exactly the missing cases,
resubmit, and compare the gathered table with the same sweep run locally
(kcreep --batch), row by row. Every daemon started is stopped by its pid,
also on failure or when the test is interrupted, and none is left defunct:
the daemons outlive local_cluster.sh start, and PID 1 on these machines never
reaps orphans, so the test makes itself their child subreaper
(prctl PR_SET_CHILD_SUBREAPER) and reaps them after local_cluster.sh stop;
local_cluster.sh run DIR -- COMMAND does the same for a command.

Skipped (exit code 77, CTest's SKIP_RETURN_CODE) with a loud message when
no cluster can be started here: not root, or slurm-wlm/munge missing. With
KCREEP_REQUIRE_SLURM=1 that is a failure instead.

    test_slurm.py PATH/TO/kcreep
"""
import ctypes
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time
import kctest as kc
import tablecmp

SKIP = 77
DEADLINE = time.time() + 270          # CTest's TIMEOUT for this test is 420 s
repo = kc.REPO
slurm_scripts = os.path.join(repo, "scripts", "slurm")
local_cluster = os.path.join(slurm_scripts, "local_cluster.sh")
run_cases = os.path.join(slurm_scripts, "run_cases_slurm.sh")

folder = kc.setup()

probe = subprocess.run([local_cluster, "check"], capture_output=True, text=True, timeout=30)
if probe.returncode != 0:
    reason = probe.stderr.strip() or probe.stdout.strip()
    banner = "#" * 78
    print(f"{banner}\n# SKIPPED: the SLURM test did not run: {reason}\n"
          f"# (it runs as root on Debian once scripts/setup.sh installed slurm-wlm and munge)\n{banner}")
    sys.stdout.flush()
    sys.exit(1 if os.environ.get("KCREEP_REQUIRE_SLURM") == "1" else SKIP)


DAEMONS = ("munged", "slurmctld", "slurmd", "slurmstepd")


def defunct_daemons():
    """{pid: name} of the defunct (zombie) SLURM and munge processes on this machine."""
    found = {}
    for entry in os.listdir("/proc"):
        if not entry.isdigit():
            continue
        try:
            with open(f"/proc/{entry}/stat") as f:
                head, tail = f.read().rsplit(")", 1)
        except OSError:
            continue
        name = head.split("(", 1)[1]
        if tail.split()[0] == "Z" and name in DAEMONS:
            found[int(entry)] = name
    return found


def reap_children(limit):
    """Reap every child of this process that ends within limit seconds."""
    end = time.time() + limit
    while time.time() < end:
        try:
            pid, _ = os.waitpid(-1, os.WNOHANG)
        except ChildProcessError:
            return
        if pid == 0:
            time.sleep(0.1)


def remaining():
    left = DEADLINE - time.time()
    if left <= 0:
        raise TimeoutError("the SLURM test ran out of time")
    return left


def run(args, env=None, timeout=60, **kw):
    return subprocess.run(args, capture_output=True, text=True, env=env, timeout=min(timeout, remaining()), **kw)


def on_signal(signum, frame):
    raise SystemExit(f"interrupted by signal {signum}")


for s in (signal.SIGTERM, signal.SIGINT, signal.SIGHUP):
    signal.signal(s, on_signal)

# Local rows (OpenBLAS with its default 2 threads here) vs SLURM rows (1 thread per
# task): measured max difference 1.7e-15 (fij relative to the largest |fij|, the
# others relative to themselves; berr is round-off in both, 6e-17 to 1e-16).
TOL = 1e-12


def compare(local_rows, slurm_rows, what):
    kc.check([r["case"] for r in slurm_rows] == [r["case"] for r in local_rows],
             f"{what}: the same cases in the same order ({len(slurm_rows)} rows)")
    for a, b in zip(local_rows, slurm_rows):
        worst, column = tablecmp.row_difference(a, b)
        kc.check(worst <= TOL, f"{what} {a['case']}: verdict {b['verdict']}, coefficients agree "
                 f"(max difference {worst:.1e} in {column or '-'} <= {TOL:.0e})")


# --- the sweep: 8 cheap cases, 10 x 10 to 24 x 24, and one bad input
sweep = []
for k in range(8):
    m = 10 + 2 * k
    # the last case in a sub-folder: named sub/p7_24 locally and after the gather
    name = f"p{k}_{m}" if k < 7 else f"sub/p{k}_{m}"
    os.makedirs(os.path.join(folder, os.path.dirname(name)), exist_ok=True)
    solver = "&solver scheme='backward', spin_shift=0.1666666666666667 /\n" if k % 3 == 2 else ""
    with open(os.path.join(folder, name + ".nml"), "w") as f:
        f.write(f"&patch semi_a=1, semi_b={1 - 0.08 * k:.2f}, mx={m}, my={m} /\n&material nu={0.1 * (k % 4):.1f} /\n"
                + solver)
    sweep.append(name + ".nml")
with open(os.path.join(folder, "bad.nml"), "w") as f:
    f.write("&material nu=0.7 /\n")
sweep.insert(5, "bad.nml")
with open(os.path.join(folder, "sweep.list"), "w") as f:
    f.write("# a small sweep\n" + "\n".join(sweep) + "\n")
n_cases = len(sweep)       # 9 cases in chunks of 2: 5 array tasks

t0 = time.time()
local = run([kc.KCREEP, "--batch", "sweep.list", "local.tab"], cwd=folder)
t_local = time.time() - t0
kc.check(local.returncode == 5, f"local batch: exit 5 (one bad case) ({local.returncode})")
local_rows = kc.read_table(os.path.join(folder, "local.tab"))
kc.check(local_rows[-1]["case"] == "sub/p7_24", f"a case in a sub-folder is named by its path ({local_rows[-1]['case']})")

# the daemons outlive `local_cluster.sh start`: as their subreaper this process
# becomes their parent and can reap them (PID 1 here never does)
defunct_before = defunct_daemons()          # other people's, left alone
PR_SET_CHILD_SUBREAPER = 36
kc.check(ctypes.CDLL(None, use_errno=True).prctl(PR_SET_CHILD_SUBREAPER, 1, 0, 0, 0) == 0,
         "this test is the child subreaper of the daemons it starts")

state = tempfile.mkdtemp(prefix="kcreep-slurm-")
os.chmod(state, 0o755)                # munged wants every folder above its socket searchable
cluster = os.path.join(state, "cluster")
daemon_pids = {}
try:
    start = run([local_cluster, "start", cluster], timeout=120)
    if start.returncode != 0:
        for log in sorted(os.listdir(os.path.join(cluster, "log"))) if os.path.isdir(cluster) else []:
            print(f"--- {log}\n" + open(os.path.join(cluster, "log", log)).read()[-3000:])
    kc.check(start.returncode == 0, f"local cluster started: {start.stdout.strip()} {start.stderr.strip()}")
    if start.returncode != 0:
        raise SystemExit(1)
    for d in ("munged", "slurmctld", "slurmd"):
        daemon_pids[d] = int(open(os.path.join(cluster, d + ".pid")).read())
    env = dict(os.environ, SLURM_CONF=os.path.join(cluster, "slurm.conf"))

    # --- first submission, held; one task is killed before it can run; release
    sub = run([run_cases, "sweep.list", "slurm.tab", "--chunk", "2", "--sbatch-arg=--hold"], env=env, cwd=folder)
    kc.check(sub.returncode == 0, f"submitted: {sub.stdout.strip()} {sub.stderr.strip()}")
    ids = re.search(r"array job (\d+) gather job (\d+)", sub.stdout)
    array_id, gather_id = ids.group(1), ids.group(2)
    killed = 3
    cancel = run(["scancel", f"{array_id}_{killed}"], env=env)
    kc.check(cancel.returncode == 0, f"array task {array_id}_{killed} cancelled on purpose {cancel.stderr.strip()}")
    release = run(["scontrol", "release", array_id], env=env)
    kc.check(release.returncode == 0, f"array released {release.stderr.strip()}")
    while run(["squeue", "-h", "-j", f"{array_id},{gather_id}", "-o", "%i"], env=env).stdout.strip():
        time.sleep(0.5)
    gather_state = run(["scontrol", "show", "job", gather_id], env=env).stdout
    kc.check("ExitCode=1:0" in gather_state, "gather job after the kill: exit 1 (cases missing)")
    kc.check(not os.path.exists(os.path.join(folder, "slurm.tab")), "no table written while cases are missing")
    workdir = os.path.join(folder, "slurm.tab.slurm")
    missing = open(os.path.join(workdir, "missing.list")).read().split()
    expected_missing = [os.path.join(folder, c) for c in sweep[2 * (killed - 1):2 * killed]]
    kc.check(missing == expected_missing, f"gather names exactly the killed task's cases: {missing}")
    log = open(os.path.join(workdir, "logs", f"gather_{gather_id}.out")).read()
    kc.check(all(p in log for p in expected_missing) and "2 of 9 cases missing" in log,
             "the gather log reports the missing cases")

    # --- resubmit the same command: only the killed chunk runs
    t0 = time.time()
    again = run([run_cases, "sweep.list", "slurm.tab", "--chunk", "2", "--wait"], env=env, cwd=folder, timeout=150)
    kc.check(again.returncode == 5, f"resubmit --wait: exit 5 (complete, one bad case) ({again.returncode}): "
             f"{again.stdout.strip()} {again.stderr.strip()}")
    kc.check("submitted 1 array task(s)" in again.stdout, "resubmit runs only the killed chunk")
    slurm_rows = kc.read_table(os.path.join(folder, "slurm.tab"))
    compare(local_rows, slurm_rows, "SLURM vs local")
    bad = [r for r in slurm_rows if r["case"] == "bad"]
    kc.check(len(bad) == 1 and bad[0]["verdict"] == "error:bad-input", "the bad case: one error row")
    comments = [l for l in open(os.path.join(folder, "slurm.tab")) if l.startswith("# case ")]
    kc.check(any(l.startswith("# case 6 ") and "nu = 0.7" in l for l in comments),
             "its message in the gathered comments, numbered by its place in the list")

    # --- --retry-failed runs again the chunk with the error row (a bad input stays bad)
    retry = run([run_cases, "sweep.list", "slurm.tab", "--chunk", "2", "--wait", "--retry-failed"], env=env,
                cwd=folder, timeout=150)
    kc.check(retry.returncode == 5 and "submitted 1 array task(s)" in retry.stdout
             and os.path.exists(os.path.join(workdir, "chunks", "00003.tab.failed")),
             f"--retry-failed reruns the one chunk with an error row ({retry.returncode})")
    compare(local_rows, kc.read_table(os.path.join(folder, "slurm.tab")), "after --retry-failed")

    # --- a third time: everything is there, nothing is submitted
    third = run([run_cases, "sweep.list", "slurm.tab", "--chunk", "2"], env=env, cwd=folder)
    kc.check("done already" in third.stdout and third.returncode == 5, f"third run gathers only: {third.stdout.strip()}")

    # --- a resubmit while jobs of the sweep are queued is refused
    os.remove(os.path.join(workdir, "chunks", "00001.tab"))
    held = run([run_cases, "sweep.list", "slurm.tab", "--chunk", "2", "--sbatch-arg=--hold"], env=env, cwd=folder)
    busy = run([run_cases, "sweep.list", "slurm.tab", "--chunk", "2"], env=env, cwd=folder)
    kc.check(held.returncode == 0 and busy.returncode == 2 and "still queued or running" in busy.stderr,
             f"second submission while the first is queued refused: {busy.stderr.strip()}")
    run(["scancel", re.search(r"array job (\d+)", held.stdout).group(1)], env=env)

    # --- the whole sweep in one go, for the wall time (printed, not asserted)
    t0 = time.time()
    full = run([run_cases, "sweep.list", "full.tab", "--chunk", "2", "--wait"], env=env, cwd=folder, timeout=150)
    t_slurm = time.time() - t0
    kc.check(full.returncode == 5, f"whole sweep through SLURM ({full.returncode})")
    compare(local_rows, kc.read_table(os.path.join(folder, "full.tab")), "whole SLURM sweep vs local")
    print(f"timing (not asserted): {n_cases} cases locally with kcreep --batch {t_local:.2f} s, "
          f"through SLURM (5 array tasks + gather, --wait) {t_slurm:.2f} s")

    # --- an input of one case changes (its mtime set back): only its chunk runs again
    changed = os.path.join(folder, sweep[2])
    old = os.path.getmtime(changed)
    with open(changed, "w") as f:
        f.write("&patch semi_a=1, semi_b=0.5, mx=14, my=14 /\n")
    os.utime(changed, (old - 3600, old - 3600))
    redo = run([run_cases, "sweep.list", "full.tab", "--chunk", "2", "--wait"], env=env, cwd=folder, timeout=150)
    kc.check(redo.returncode == 5 and "submitted 1 array task(s)" in redo.stdout
             and "chunk 2: its cases' inputs changed" in redo.stdout,
             f"a changed namelist: its chunk alone runs again ({redo.returncode}) {redo.stdout.strip()}")
    redo_rows = kc.read_table(os.path.join(folder, "full.tab"))
    ratio = redo_rows[2]["c"] ** 2 if redo_rows else None       # c^2 = a b = 0.5 now
    kc.check(ratio is not None and abs(ratio - 0.5) < 1e-9, f"the gathered row is the new case's (c^2 = {ratio})")
    compare(local_rows[:2] + local_rows[3:], redo_rows[:2] + redo_rows[3:], "the other cases after the rerun")

    # --- defect 1 of issue 31: the mask file of a case changes (contents only, its
    # mtime set back): the input fingerprint (kcreep --fingerprint) sees it
    def mask_text(cells):
        rows = ["".join("1" if 12 * j + i < cells else "0" for i in range(12)) for j in range(12)]
        return "12 12 0.1 0.1 0 0\n" + "\n".join(rows) + "\n"

    mask_path = os.path.join(folder, "fp.mask")
    with open(mask_path, "w") as f:
        f.write(mask_text(100))
    with open(changed, "w") as f:
        f.write("&patch shape='mask', mask_file='fp.mask' /\n&solver method='dense', target_error=0 /\n")
    first = run([run_cases, "sweep.list", "full.tab", "--chunk", "2", "--wait"], env=env, cwd=folder, timeout=150)
    cells = [r["n"] for r in kc.read_table(os.path.join(folder, "full.tab"))][2:3]
    kc.check(first.returncode == 5 and cells == [100], f"the case now reads a mask: 100 cells ({cells})")
    old = os.path.getmtime(mask_path)
    with open(mask_path, "w") as f:
        f.write(mask_text(80))
    os.utime(mask_path, (old - 3600, old - 3600))
    redo = run([run_cases, "sweep.list", "full.tab", "--chunk", "2", "--wait"], env=env, cwd=folder, timeout=150)
    cells = [r["n"] for r in kc.read_table(os.path.join(folder, "full.tab"))][2:3]
    kc.check(redo.returncode == 5 and "submitted 1 array task(s)" in redo.stdout
             and "chunk 2: its cases' inputs changed" in redo.stdout and cells == [80],
             f"its mask file rewritten: its chunk alone runs again, 80 cells ({cells}) ({redo.returncode}) "
             f"{redo.stdout.strip()[-200:]} {redo.stderr.strip()[-300:]}")

    # --- issue 45, item 1: contact tables (&wheel_rail) through SLURM, with and
    # without &fastsim and &rolling: each case's .wr, one block of rows per case in
    # the gathered table, the rows the local kcreep --batch writes
    tables = {"w_plain": kc.s1002_case(), "w_fast": kc.s1002_case("&fastsim " + kc.S1002_CREEP + "\n"),
              "w_roll": kc.s1002_case("&rolling " + kc.S1002_CREEP + "\n")}
    kc.check(tables["w_plain"] is not None, f"the profiles of input/s1002_uic60.nml at {kc.PROFILES}")
    if tables["w_plain"] is not None:
        for name, text in tables.items():
            with open(os.path.join(folder, name + ".nml"), "w") as f:
                f.write(text)
        with open(os.path.join(folder, "tables.list"), "w") as f:
            f.write("".join(name + ".nml\n" for name in tables))
        one = dict(os.environ, OMP_NUM_THREADS="1")       # as each array task runs (1 CPU per task)
        local_wr = run([kc.KCREEP, "--batch", "tables.list", "tables_local.tab"], env=one, cwd=folder, timeout=120)
        local_wr_rows = kc.read_table(os.path.join(folder, "tables_local.tab")) if local_wr.returncode == 0 else []
        wr = run([run_cases, "tables.list", "tables_slurm.tab", "--chunk", "2", "--wait"], env=env, cwd=folder,
                 timeout=150)
        slurm_wr_rows = kc.read_table(os.path.join(folder, "tables_slurm.tab")) if wr.returncode == 0 else []
        kc.check(wr.returncode == 0 and len(local_wr_rows) == 6 and
                 [r["case"] for r in slurm_wr_rows] == [r["case"] for r in local_wr_rows] ==
                 ["w_plain"] * 2 + ["w_fast"] * 2 + ["w_roll"] * 2,
                 f"contact tables through SLURM: 3 cases, 2 rows each, as locally ({wr.returncode}: "
                 f"{wr.stdout.strip()[-200:]} {wr.stderr.strip()[-300:]})")
        worst = max([abs(a[c] - b[c]) / max(abs(a[c]), 1e-300) for a, b in zip(local_wr_rows, slurm_wr_rows)
                     for c in ("fn", "c11", "c22", "c23") if a[c] == a[c]] + [0.0])
        kc.check(slurm_wr_rows and worst <= TOL, f"contact tables: SLURM rows = local rows (max relative "
                 f"difference {worst:.1e} <= {TOL:.0e})")
        kc.check(all(os.path.exists(os.path.join(folder, f)) for f in ["w_plain.wr", "w_fast.creep", "w_roll.roll"]),
                 "each case's own files written by its array task")
        with open(os.path.join(folder, "mixed.list"), "w") as f:
            f.write("w_plain.nml\n" + sweep[0] + "\n")
        mixed = run([run_cases, "mixed.list", "mixed.tab"], env=env, cwd=folder)
        kc.check(mixed.returncode == 2 and "one kind" in mixed.stderr and
                 not os.path.exists(os.path.join(folder, "mixed.tab.slurm")),
                 f"a list mixing contact tables and single patches refused before submitting: {mixed.stderr.strip()}")
finally:
    stop = subprocess.run([local_cluster, "stop", cluster], capture_output=True, text=True, timeout=90)
    if stop.returncode != 0:
        print(stop.stdout + stop.stderr)

    def alive(pid):
        try:
            with open(f"/proc/{pid}/stat") as f:
                return f.read().rsplit(")", 1)[1].split()[0] != "Z"
        except OSError:
            return False

    still = {d: p for d, p in daemon_pids.items() if alive(p)}
    kc.check(not still, f"every daemon stopped ({daemon_pids}, still running: {still})")
    reap_children(15)
    left = {p: d for p, d in defunct_daemons().items() if p not in defunct_before}
    kc.check(not left, f"no defunct daemon left after stop (defunct: {left})")

    # `run DIR -- COMMAND`: start, the command, stop and reaping in one process
    if remaining() > 60:
        ran = run([local_cluster, "run", os.path.join(state, "cluster2"), "--", "sinfo", "-h", "-o", "%T"],
                  timeout=90)
        kc.check(ran.returncode == 0 and ran.stdout.strip().endswith("idle"),
                 f"local_cluster.sh run: the command sees the idle node ({ran.returncode}: {ran.stdout.strip()})")
        left = {p: d for p, d in defunct_daemons().items() if p not in defunct_before}
        kc.check(not left, f"no defunct daemon left after local_cluster.sh run (defunct: {left})")
        reap_children(5)
    shutil.rmtree(state, ignore_errors=True)
kc.finish()
