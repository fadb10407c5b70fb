"""kcreep --batch: one table for many cases, in list order; a failing case
gets an error row and the batch goes on; the rows equal single-case runs;
a batch killed in the middle resumes from OUT.partial without redoing or
losing finished rows; --estimate-memory."""
import math
import os
import signal
import subprocess
import sys
import time
import kctest as kc
import tablecmp

folder = kc.setup()
sub = os.path.join(folder, "sub")
os.makedirs(sub)

# Same binary, same machine, same case: measured max difference 0 between single
# and batch runs and between resumed and uninterrupted batches; 1e-12 leaves room
# for a threaded BLAS summing in another order (tablecmp says how it is measured).
TOL = 1e-12


def write(path, text):
    with open(path, "w") as f:
        f.write(text)


def same_numbers(a, b, what):
    worst, column = tablecmp.row_difference(a, b)
    kc.check(worst <= TOL, f"{what}: coefficients agree (max difference {worst:.1e} in {column or '-'} <= {TOL:.0e})")


def batch(list_name, table=None, cwd=folder, env=None):
    args = [kc.KCREEP, "--batch", list_name] + ([table] if table else [])
    return subprocess.run(args, cwd=cwd, capture_output=True, text=True, env=env)


# --- a mixed list: good cases, a bad input, a missing file, a mask relative to its namelist
cases = {
    # grids exactly as given (target_error = 0): a 10 x 10 grid cannot meet a target
    "e10": "&patch semi_a=1, semi_b=0.6, mx=10, my=10 /\n&solver target_error=0 /\n",
    "e16b": "&patch semi_a=0.5, semi_b=1, mx=16, my=16 /\n&solver scheme='backward', target_error=0 /\n",
    "bad": "&patch shape='circle' /\n",
    "m": "&patch shape='mask', mask_file='m.mask' /\n",
    "elong": "&patch semi_a=5, semi_b=1, mx=12, my=12 /\n",   # flagged: elongated cells
}
for name, text in cases.items():
    write(os.path.join(sub, name + ".nml"), text)
write(os.path.join(sub, "m.mask"), "4 3 0.25 0.25 -0.375 -0.25\n.##.\n####\n.##.\n")
write(os.path.join(folder, "cases.list"),
      "# sweep\nsub/e10.nml\n\n  sub/bad.nml  \nsub/e16b.nml\nsub/missing.nml\n" + os.path.join(sub, "m.nml") +
      "\nsub/elong.nml\n")
proc = batch("cases.list")
table_path = os.path.join(folder, "cases.tab")
kc.check(proc.returncode == 5, f"exit status 5 when cases failed (got {proc.returncode})")
rows = kc.read_table(table_path) if os.path.exists(table_path) else []
names = [r["case"] for r in rows]
# named by the path relative to the list (the absolute entry of m.nml too)
kc.check(names == ["sub/e10", "sub/bad", "sub/e16b", "sub/missing", "sub/m", "sub/elong"],
         f"one row per case in list order: {names}")
errs = proc.stderr.strip().splitlines()
kc.check(any(l.startswith("kcreep: case 2 'sub/bad.nml': error: ") and "shape = 'circle'" in l for l in errs),
         "the bad case's message on stderr, prefixed with the case")
kc.check(any(l.startswith("kcreep: case 4 'sub/missing.nml': error: ") for l in errs), "missing namelist reported")
kc.check(any(l.startswith("kcreep: case 6 'sub/elong.nml': warning: ") for l in errs), "warning of case 6 prefixed")
kc.check(errs[-1].startswith("kcreep: error: 2 case(s)"), f"last line says how many failed: {errs[-1]!r}")
comments = [l for l in open(table_path) if l.startswith("#")]
kc.check(any("case 2 'sub/bad.nml': error:" in l for l in comments), "error message in the table comments")
kc.check(comments[-1].split()[1:] == list(rows[0].keys()), "last comment line names the columns")
if len(rows) == 6:
    kc.check(rows[1]["verdict"] == "error:bad-input" and rows[3]["verdict"] == "error:bad-input",
             f"error rows say error:bad-input ({rows[1]['verdict']}, {rows[3]['verdict']})")
    kc.check(all(math.isnan(rows[1][c]) for c in ["f11", "f22", "f23", "c11", "t_total"]), "error row has NaN")
    # 10 x 10 and 16 x 16 are too coarse to estimate their error: no ok without an estimate (issue 45)
    kc.check(rows[0]["verdict"] == "uncertain" and rows[2]["verdict"] == "uncertain",
             f"good cases run, uncertain without an estimate ({rows[0]['verdict']}, {rows[2]['verdict']})")
    kc.check(rows[5]["verdict"] != "ok", f"elongated cells flagged in the batch too ({rows[5]['verdict']})")
    # each good row equals the single-case run of the same namelist, run in its folder
    for k, name in [(0, "e10"), (2, "e16b"), (4, "m"), (5, "elong")]:
        single = subprocess.run([kc.KCREEP, name + ".nml"], cwd=sub, capture_output=True, text=True)
        kc.check(single.returncode == 0, f"single run of {name}")
        ref = kc.read_table(os.path.join(sub, name + ".tab"))[0]
        kc.check(ref["verdict"] == rows[k]["verdict"], f"{name}: same verdict {ref['verdict']}")
        same_numbers(ref, rows[k], f"{name}: batch row vs single run")
kc.check(not os.path.exists(table_path + ".partial"), "no partial table left after a finished batch")

# --- a list without failures exits 0; the default table name and an explicit one
write(os.path.join(folder, "good.list"), "sub/e10.nml\nsub/e16b.nml\n")
proc = batch("good.list", "out.tab")
kc.check(proc.returncode == 0 and os.path.exists(os.path.join(folder, "out.tab")), f"all good: exit 0 ({proc.stderr})")

# --- errors of the batch itself: one line, status 2, no table
for name, text, fragment in [("empty.list", "# nothing\n\n", "no cases"), ("nowhere.list", None, "cannot open")]:
    if text is not None:
        write(os.path.join(folder, name), text)
    proc = batch(name, "x.tab")
    lines = proc.stderr.strip().splitlines()
    kc.check(proc.returncode == 2 and len(lines) == 1 and fragment in lines[0],
             f"{name}: status 2 and one line ({proc.returncode}, {proc.stderr.strip()!r})")
    kc.check(not os.path.exists(os.path.join(folder, "x.tab")), f"{name}: no table written")
proc = batch("good.list", "no/such/folder/x.tab")
kc.check(proc.returncode == 4 and "batch table" in proc.stderr, f"unwritable table: status 4 ({proc.stderr.strip()!r})")

# --- kill a batch in the middle, resume, compare with an uninterrupted run
sweep = []
# dense 60 x 60 cases take ~0.5 s each here: time enough to kill the batch between two
for k, m in enumerate([10, 12, 60, 60, 60]):
    name = f"s{k}_{m}"
    write(os.path.join(sub, name + ".nml"),
          f"&patch semi_a=1, semi_b={0.5 + 0.1 * k}, mx={m}, my={m} /\n&solver method='dense' /\n")
    sweep.append("sub/" + name + ".nml")
write(os.path.join(folder, "sweep.list"), "\n".join(sweep) + "\n")
ref_proc = batch("sweep.list", "reference.tab")
kc.check(ref_proc.returncode == 0, "uninterrupted sweep")
reference = kc.read_table(os.path.join(folder, "reference.tab"))

partial = os.path.join(folder, "resumed.tab.partial")
victim = subprocess.Popen([kc.KCREEP, "--batch", "sweep.list", "resumed.tab"], cwd=folder,
                          stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
deadline = time.time() + 60
done_before_kill = 0
while time.time() < deadline and victim.poll() is None:
    if os.path.exists(partial):
        done_before_kill = sum(1 for l in open(partial) if l.strip() and not l.startswith("#"))
        if done_before_kill >= 2:
            break
    time.sleep(0.005)
victim.send_signal(signal.SIGKILL)
victim.wait()
kept_partial = open(partial).read() if os.path.exists(partial) else ""
kc.check(2 <= done_before_kill < len(sweep) and not os.path.exists(os.path.join(folder, "resumed.tab")),
         f"killed in the middle: {done_before_kill} of {len(sweep)} rows in the partial table, no final table")
proc = batch("sweep.list", "resumed.tab")
kc.check(proc.returncode == 0, f"resumed batch finishes ({proc.stderr.strip()})")
kc.check(f"{done_before_kill} of {len(sweep)} cases already done" in proc.stdout,
         f"resume skips the finished cases: {proc.stdout.splitlines()[:1]}")
ran = [l for l in proc.stdout.splitlines() if l.startswith("kcreep: ") and "/5 " in l]
kc.check(len(ran) == len(sweep) - done_before_kill, f"only the remaining cases ran ({len(ran)})")
resumed = kc.read_table(os.path.join(folder, "resumed.tab"))
kc.check([r["case"] for r in resumed] == [r["case"] for r in reference], "resumed table: every case once, in order")
for a, b in zip(reference, resumed):
    same_numbers(a, b, f"{a['case']}: resumed vs uninterrupted")

# a torn last line (killed in the middle of a write) is dropped and that case run again
torn = os.path.join(folder, "torn.tab.partial")
text = kept_partial.rstrip("\n")
cut = text.rfind("\n")
write(torn, text[:cut + 1] + text[cut + 1:cut + 40])      # the last row loses its end
proc = batch("sweep.list", "torn.tab")
kc.check(proc.returncode == 0 and f"{done_before_kill - 1} of {len(sweep)} cases already done" in proc.stdout,
         f"torn last row dropped and its case run again: {proc.stdout.splitlines()[:1]}")
torn_rows = kc.read_table(os.path.join(folder, "torn.tab"))
kc.check([r["case"] for r in torn_rows] == [r["case"] for r in reference], "torn: every case once, in order")
for a, b in zip(reference, torn_rows):
    same_numbers(a, b, f"{a['case']}: after a torn row vs uninterrupted")

# --- defect 1 of issue 31: a case whose mask file changes after the interruption
# is run again on resume (the row's input fingerprint, kcreep --fingerprint, is
# written beside it in the partial table); the unchanged cases are kept
def mask_text(cells):
    rows = ["".join("1" if 12 * j + i < cells else "0" for i in range(12)) for j in range(12)]
    return "12 12 0.1 0.1 0 0\n" + "\n".join(rows) + "\n"


write(os.path.join(sub, "fp_mask.nml"), "&patch shape='mask', mask_file='fp.mask' /\n&solver method='dense', target_error=0 /\n")
write(os.path.join(sub, "fp.mask"), mask_text(100))
write(os.path.join(folder, "fp.list"), "sub/fp_mask.nml\nsub/s1_12.nml\n" + "\n".join(sweep[2:]) + "\n")
fp_partial = os.path.join(folder, "fp.tab.partial")
victim = subprocess.Popen([kc.KCREEP, "--batch", "fp.list", "fp.tab"], cwd=folder,
                          stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
deadline = time.time() + 60
fp_done = 0
while time.time() < deadline and victim.poll() is None:
    if os.path.exists(fp_partial):
        fp_done = sum(1 for l in open(fp_partial) if l.strip() and not l.startswith("#"))
        if fp_done >= 2:
            break
    time.sleep(0.005)
victim.send_signal(signal.SIGKILL)
victim.wait()
marks = [l.split() for l in open(fp_partial) if l.startswith("# fingerprint ")]
printed = subprocess.run([kc.KCREEP, "--fingerprint", "sub/fp_mask.nml"], cwd=folder, capture_output=True,
                         text=True).stdout.split()
kc.check(2 <= fp_done < 5 and marks and marks[0][2:4] == ["1", printed[0]],
         f"killed after {fp_done} rows; the partial table holds each row's fingerprint, "
         f"that of kcreep --fingerprint ({marks[:1]}, {printed[:1]})")
old = os.path.getmtime(os.path.join(sub, "fp.mask"))
write(os.path.join(sub, "fp.mask"), mask_text(80))
os.utime(os.path.join(sub, "fp.mask"), (old - 3600, old - 3600))     # an older mtime: contents decide
proc = batch("fp.list", "fp.tab")
kc.check(proc.returncode == 0 and "case 1 'sub/fp_mask.nml': its inputs changed" in proc.stdout.replace(folder + "/", "")
         and f"{fp_done - 1} of 5 cases already done" in proc.stdout,
         f"resume after the mask changed: case 1 named and run again, the other {fp_done - 1} kept: "
         f"{proc.stdout.splitlines()[:2]}")
ran = [l.split()[1] for l in proc.stdout.splitlines() if l.startswith("kcreep: ") and "/5 " in l]
kc.check(ran[:1] == ["1/5"] and len(ran) == 5 - (fp_done - 1), f"the changed case and the remaining ones ran ({ran})")
fp_rows = kc.read_table(os.path.join(folder, "fp.tab"))
kc.check([r["case"] for r in fp_rows] == ["sub/fp_mask", "sub/s1_12"] + [r["case"] for r in reference[2:]]
         and fp_rows[0]["n"] == 80, f"the table: rows in list order, the masked case with its new 80 cells "
         f"({[r['case'] for r in fp_rows]}, n = {fp_rows[0]['n'] if fp_rows else None})")
kc.check(not any(l.startswith("# fingerprint") for l in open(os.path.join(folder, "fp.tab"))),
         "the finished table carries no fingerprint lines")

# a partial table of another list, left by a batch that was killed (its lock
# went with it), blocks nothing: it is kept as OTHER.partial.<its list's
# signature>, this list runs afresh, and the first list resumes from it later
write(os.path.join(folder, "other.tab.partial"), kept_partial)
proc = batch("good.list", "other.tab")
aside = [f for f in os.listdir(folder) if f.startswith("other.tab.partial.")]
kc.check(proc.returncode == 0 and os.path.exists(os.path.join(folder, "other.tab")) and "kept as" in proc.stdout
         and len(aside) == 1 and open(os.path.join(folder, aside[0])).read() == kept_partial,
         f"another list's partial kept aside ({aside}), this list done: {proc.returncode} {proc.stdout.splitlines()[:1]}")
proc = batch("sweep.list", "other.tab")
kc.check(proc.returncode == 0 and "resuming from" in proc.stdout
         and f"{done_before_kill} of {len(sweep)} cases already done" in proc.stdout
         and not any(f.startswith("other.tab.partial") for f in os.listdir(folder)),
         f"its own list resumes from the kept partial, which is then gone: {proc.stdout.splitlines()[:2]}")
other_rows = kc.read_table(os.path.join(folder, "other.tab"))
kc.check([r["case"] for r in other_rows] == [r["case"] for r in reference], "resumed from the kept partial: in order")

# --- issue 45, item 1: contact tables (&wheel_rail) in a batch. Each case writes
# its .wr (and .creep/.roll with &fastsim/&rolling) as a single run started in the
# batch's working folder does, and its rows go to the batch table led by the case's name.
# (Before: the default unit circle was solved, one row, no .wr; with &fastsim a
# segmentation fault, the normal pressure of a normal solve that never ran.)
wr_dir = os.path.join(folder, "wr")
os.makedirs(wr_dir)
one_thread = dict(os.environ, OMP_NUM_THREADS="1")   # (item 2 of issue 45 is another's: keep this test fast)
wr_cases = {"plain": kc.s1002_case(), "fast": kc.s1002_case("&fastsim " + kc.S1002_CREEP + "\n"),
            "roll": kc.s1002_case("&rolling " + kc.S1002_CREEP + "\n"),
            "nowheel": (kc.s1002_case() or "").replace("MBench_S1002_v3.prw", "no_such_wheel.prw")}
if wr_cases["plain"] is None:
    kc.check(False, f"the profiles of input/s1002_uic60.nml are not at {kc.PROFILES}")
else:
    for name, text in wr_cases.items():
        write(os.path.join(wr_dir, name + ".nml"), text)
    write(os.path.join(folder, "wr.list"), "wr/plain.nml\nwr/fast.nml\nwr/nowheel.nml\nwr/roll.nml\n")
    proc = batch("wr.list", "wr.tab", env=one_thread)
    kc.check(proc.returncode == 5 and "segmentation" not in proc.stderr.lower(),
             f"contact tables in a batch: exit 5 for the one bad case ({proc.returncode}, {proc.stderr.strip()[-300:]!r})")
    wr_rows = kc.read_table(os.path.join(folder, "wr.tab")) if os.path.exists(os.path.join(folder, "wr.tab")) else []
    kc.check(all(os.path.exists(os.path.join(folder, f)) for f in ["plain.wr", "fast.wr", "fast.creep", "roll.wr",
                                                                 "roll.roll"]),
             f"each case's own files in the working folder: {sorted(os.listdir(folder))}")
    by_case = {}
    for r in wr_rows:
        by_case.setdefault(r["case"], []).append(r)
    kc.check(list(by_case) == ["wr/plain", "wr/fast", "wr/nowheel", "wr/roll"],
             f"the case's name leads each row, cases in list order: {list(by_case)}")
    for name in ["plain", "fast", "roll"]:
        own = kc.read_table(os.path.join(folder, name + ".wr")) if os.path.exists(os.path.join(folder, name + ".wr")) else []
        got = by_case.get("wr/" + name, [])
        kc.check(len(own) == 2 and len(got) == len(own) and
                 all({k: v for k, v in a.items() if k != "case"} == b for a, b in zip(got, own)),
                 f"{name}: the batch rows are the rows of its .wr ({len(got)} and {len(own)} rows, 2 shifts)")
    bad = by_case.get("wr/nowheel", [{}])
    kc.check(len(bad) == 1 and bad[0].get("verdict") == "error:bad-input" and math.isnan(bad[0].get("c11", 0.0)),
             f"the case that cannot run: one NaN row, error:bad-input ({bad})")
    comments = [l for l in open(os.path.join(folder, "wr.tab")) if l.startswith("#")] if wr_rows else []
    kc.check(comments and comments[-1].split()[1:] == list(wr_rows[0].keys()) and comments[-1].split()[1] == "case"
             and any(l.startswith("# case 1 'wr/plain.nml': ") and "S1002" in l for l in comments),
             "the column line starts with case; each case's profiles in its comments")

    # resumable: killed after its first case, the batch resumes with the others;
    # a block whose rows were cut short (a kill while they were written) runs again
    write(os.path.join(folder, "wr3.list"), "wr/plain.nml\nwr/fast.nml\nwr/roll.nml\n")
    wr_partial = os.path.join(folder, "wr3.tab.partial")
    victim = subprocess.Popen([kc.KCREEP, "--batch", "wr3.list", "wr3.tab"], cwd=folder, env=one_thread,
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    deadline = time.time() + 120
    while time.time() < deadline and victim.poll() is None:
        if os.path.exists(wr_partial) and sum(l.startswith("# fingerprint ") for l in open(wr_partial)) >= 1:
            time.sleep(0.05)     # the block's rows follow its mark in the same flush
            break
        time.sleep(0.01)
    victim.send_signal(signal.SIGKILL)
    victim.wait()
    killed = open(wr_partial).read() if os.path.exists(wr_partial) else ""
    marks = [l.split() for l in killed.splitlines() if l.startswith("# fingerprint ")]
    kc.check(len(marks) >= 1 and marks[0][2] == "1" and marks[0][4] == "2" and
             not os.path.exists(os.path.join(folder, "wr3.tab")),
             f"killed after case 1: its mark says its 2 rows ({marks[:1]}), no final table")
    if len(marks) == 1:
        proc = batch("wr3.list", "wr3.tab", env=one_thread)
        kc.check(proc.returncode == 0 and "1 of 3 cases already done" in proc.stdout and
                 sum(l.startswith("kcreep: ") and "/3 " in l for l in proc.stdout.splitlines()) == 2,
                 f"resumed: case 1 kept, the 2 others run ({proc.stdout.splitlines()[:1]})")
        resumed_wr = kc.read_table(os.path.join(folder, "wr3.tab"))
        kc.check([r["case"] for r in resumed_wr] == [r["case"] for r in wr_rows if r["case"] != "wr/nowheel"] and
                 all(a == b for a, b in zip(resumed_wr, [r for r in wr_rows if r["case"] != "wr/nowheel"])),
                 "the resumed table: the rows of the uninterrupted one")
        cut = killed.rstrip("\n").split("\n")
        write(os.path.join(folder, "wr4.tab.partial"), "\n".join(cut[:-1]) + "\n")   # case 1 lost its 2nd row
        write(os.path.join(folder, "wr4.list"), open(os.path.join(folder, "wr3.list")).read())
        proc = batch("wr4.list", "wr4.tab", env=one_thread)
        kc.check(proc.returncode == 0 and "already done" not in proc.stdout and
                 len(kc.read_table(os.path.join(folder, "wr4.tab"))) == 6,
                 f"a block cut short is run again: {proc.stdout.splitlines()[:1]}")

    # one table holds one kind: a list mixing contact tables and single patches is refused at once
    write(os.path.join(folder, "mixed.list"), "sub/e10.nml\nwr/plain.nml\n")
    proc = batch("mixed.list", "mixed.tab")
    kc.check(proc.returncode == 2 and len(proc.stderr.strip().splitlines()) == 1 and "one kind" in proc.stderr
             and not os.path.exists(os.path.join(folder, "mixed.tab.partial")),
             f"a mixed list refused in one line: {proc.returncode} {proc.stderr.strip()!r}")

# --- --estimate-memory: what the case's solve path allocates, plus a little.
# method = 'dense' on a y-symmetric ellipse: the two half systems of n unknowns,
# one matrix buffer of 8 n^2 bytes; 'auto' on 80 x 80 takes the iterative path.
write(os.path.join(sub, "it80.nml"), "&patch semi_a=1, semi_b=0.8, mx=80, my=80 /\n&solver method='iterative' /\n")
est = subprocess.run([kc.KCREEP, "--estimate-memory", "sub/s2_60.nml", "sub/e10.nml", "sub/m.nml", "sub/it80.nml"],
                     cwd=folder, capture_output=True, text=True)
# one line 'FILE BYTES PATH' per file
values = [int(l.rsplit(" ", 2)[1]) for l in est.stdout.strip().splitlines()]
n60 = reference[2]["n"]
dense = 8 * n60 ** 2
kc.check(est.returncode == 0 and len(values) == 4, f"one estimate per file: {est.stdout.split()}")
# (m.nml, an 8-cell mask, is split under error control up to the cell budget,
# 40,000 cells at the default target: its finest split takes the iterative path)
kc.check([l.rsplit(" ", 2)[2] for l in est.stdout.strip().splitlines()] == ["dense", "dense", "iterative", "iterative"],
         f"the solve path of each: {est.stdout.strip()}")
# measured (GNU time, OPENBLAS_NUM_THREADS=1, unit circle): dense 80 x 80 estimate 205e6 B,
# peak RSS 227e6 B; dense 40 x 40 13.5e6 / 26.5e6 B (the program itself adds 10-20 MB);
# iterative 200 x 200 155e6 / 138e6 B, 400 x 400 792e6 / 553e6 B (the estimate stays above)
# (now src/solve/kcreep_solve_memory.f90: 8 n^2 + 3400 n + 3 MiB, the table and
# the program's 11 MB: dense 60 x 60 88.9 MB against a peak of 86.8 MB)
kc.check(dense + 11e6 <= values[0] <= dense + 4000 * n60 + 16e6,
         f"dense 60 x 60: estimate {values[0]} between 8 n^2 + 11 MB and 8 n^2 + 4000 n + 16 MB (8 n^2 = {dense})")
n80 = 5024 * 0.8   # about: the 80 x 80 ellipse with b/a = 0.8 has as many cells as 0.8 of the circle
kc.check(0 < values[3] < 8 * n80 ** 2 / 4, f"iterative 80 x 80: estimate {values[3]} far below a dense matrix")
kc.check(values[2] >= 8 * (2 * 10) ** 2, "mask case relative to its namelist folder: estimated")
# under error control the estimate is that of the finest level kcreep may choose
# (the cell budget), not of the namelist's grid; the default ellipse run is
# answered from the refined table (0 bytes, path 'table'). Checked against the
# peak RSS of the run itself (a child process of a fresh interpreter, so that
# ru_maxrss is this run's), less the program's own 10-20 MB (measured above).
write(os.path.join(sub, "ctl.nml"), "&patch semi_a=1, semi_b=1 /\n&solver method='iterative' /\n&output table_file='' /\n")
write(os.path.join(sub, "ctl_small.nml"),
      "&patch semi_a=1, semi_b=1 /\n&solver method='iterative', cell_budget=5000 /\n&output table_file='' /\n")
write(os.path.join(sub, "tbl.nml"), "&patch semi_a=1, semi_b=1 /\n&output table_file='' /\n")
est = subprocess.run([kc.KCREEP, "--estimate-memory", "sub/ctl.nml", "sub/ctl_small.nml", "sub/tbl.nml"],
                     cwd=folder, capture_output=True, text=True)
fields = [l.rsplit(" ", 2) for l in est.stdout.strip().splitlines()]
kc.check(est.returncode == 0 and [f[2] for f in fields] == ["iterative", "iterative", "table"] and
         int(fields[2][1]) == 0, f"error control and table estimates: {est.stdout.strip()}")
peak = subprocess.run([sys.executable, "-c", "import resource, subprocess, sys; "
                       "subprocess.run(sys.argv[1:], capture_output=True, check=True); "
                       "print(resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss * 1024)",
                       kc.KCREEP, "sub/ctl.nml"], cwd=folder, capture_output=True, text=True)
rss = int(peak.stdout.strip() or 0)
kc.check(peak.returncode == 0 and int(fields[0][1]) >= rss - 20e6,
         f"solved ellipse under error control: estimate {int(fields[0][1])} B covers the run's peak RSS {rss} B "
         f"less 20 MB")
kc.check(int(fields[1][1]) < int(fields[0][1]) / 3,
         f"cell_budget 5000: estimate {fields[1][1]} B well below the default budget's {fields[0][1]} B")
# a run whose GMRES fills its whole Krylov basis (restart 30, tolerance 1e-15: 38
# iterations on the 300 x 300 circle with the preconditioner that follows the
# patch's edge; with restart 50 the estimate measured 270 MB, the peak RSS 171 MB):
# the estimate counts every vector the basis may hold, not the iterations of a typical run
write(os.path.join(sub, "full_basis.nml"), "&patch semi_a=1, semi_b=1, mx=300, my=300 /\n"
      "&solver method='iterative', target_error=0, tolerance=1e-15, restart=30, max_iterations=60 /\n"
      "&output table_file='' /\n")
est = subprocess.run([kc.KCREEP, "--estimate-memory", "sub/full_basis.nml"], cwd=folder, capture_output=True, text=True)
peak = subprocess.run([sys.executable, "-c", "import resource, subprocess, sys; "
                       "out = subprocess.run(sys.argv[1:], capture_output=True, text=True, check=True).stdout; "
                       "print(resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss * 1024, "
                       "out.split(' iterations,')[0].split()[-1])",
                       kc.KCREEP, "sub/full_basis.nml"], cwd=folder, capture_output=True, text=True)
rss, iterations = (peak.stdout.split() + ["0", "0"])[:2]
estimate = int(est.stdout.rsplit(" ", 2)[1])
kc.check(peak.returncode == 0 and int(iterations) > 30 and estimate >= int(rss),
         f"GMRES through its whole basis ({iterations} iterations): estimate {estimate} B covers the peak RSS {rss} B")
# issue 45, item 6: a contact table's estimate is a bound of its levels up to the
# cell budget, calibrated on peaks (kcreep_solve_memory: 1.22-1.32 times them where
# the ladder runs to the budget; it was 1.45 times here, 5-12 times a table's peak
# overall). S1002 at shift 0, target 1e-5 so that the ladder reaches its budget of
# 40,000 cells (35,308 reached), one thread: measured peak 107.5 MB.
budget_case = kc.s1002_case(target_error=1e-5)
if budget_case is not None:
    budget_case = budget_case.replace("shift_to = 1", "shift_to = 0").replace(
        "target_error = 1e-05 /", "target_error = 1e-5, cell_budget = 40000, threads = 1 /")
    write(os.path.join(sub, "wr_budget.nml"), budget_case)
    est = subprocess.run([kc.KCREEP, "--estimate-memory", "sub/wr_budget.nml"], cwd=folder, capture_output=True,
                         text=True)
    peak = subprocess.run([sys.executable, "-c", "import resource, subprocess, sys; "
                           "subprocess.run(sys.argv[1:], capture_output=True, check=True); "
                           "print(resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss * 1024)",
                           kc.KCREEP, "sub/wr_budget.nml"], cwd=folder, capture_output=True, text=True,
                          env=dict(os.environ, OMP_NUM_THREADS="1"))
    estimate, rss = int(est.stdout.rsplit(" ", 2)[1] or 0), int(peak.stdout.strip() or 0)
    kc.check(est.returncode == 0 and peak.returncode == 0 and rss <= estimate <= 1.35 * rss,
             f"contact table at its cell budget: estimate {estimate / 1e6:.1f} MB between the peak "
             f"{rss / 1e6:.1f} MB and 1.35 times it")
    # the bound follows &solver cell_budget (the user's lever), and each shift run at once
    sizes = []
    for b, th in [(10000, 1), (160000, 1), (160000, 2)]:
        text = budget_case.replace("cell_budget = 40000, threads = 1", f"cell_budget = {b}, threads = {th}")
        write(os.path.join(sub, f"wr_b{b}_{th}.nml"), text.replace("shift_to = 0", f"shift_to = {th - 1}"))
        out = subprocess.run([kc.KCREEP, "--estimate-memory", f"sub/wr_b{b}_{th}.nml"], cwd=folder,
                             capture_output=True, text=True).stdout
        sizes.append(int(out.rsplit(" ", 2)[1]) if out.strip() else 0)
    kc.check(0 < sizes[0] < estimate < sizes[1] < sizes[2] < 2 * sizes[1],
             f"the estimate grows with the budget and the shifts at once: {[s / 1e6 for s in sizes]} MB")
# issue 45, item 6: at the default target (no cell budget given) a table's estimate
# is a limit the run holds to, not the whole cell budget: the geometry and normal
# problems of every shift are solved, each patch's ladder counted up to
# region_max_level (172) cells across its contact area, where the run stops it
# (kcreep_solve_memory region_patch_bytes). Shifts 0 and 1 mm stop at 112 and 128
# across. Measured (GNU time, one shift at a time, then two at once): estimates
# 93.2 / 170.5 MB against peaks of 65.9 / 86.0 MB (1.42 / 1.98 times); before,
# 465 / 909 MB (7.1 / 10.6 times). A patch stopping below the limit is counted
# at it (the 3-shift table 0, 3, 6 mm: 1.79 / 2.26 times): the stated ratio is 2.5.
cheap = kc.s1002_case(target_error=1e-3)
if cheap is not None:
    for th in (1, 2):
        write(os.path.join(sub, f"wr_cheap_{th}.nml"),
              cheap.replace("target_error = 0.001 /", f"target_error = 0.001, threads = {th} /"))
        est = subprocess.run([kc.KCREEP, "--estimate-memory", f"sub/wr_cheap_{th}.nml"], cwd=folder,
                             capture_output=True, text=True)
        peak = subprocess.run([sys.executable, "-c", "import resource, subprocess, sys; "
                               "out = subprocess.run(sys.argv[1:], capture_output=True, text=True, check=True).stdout; "
                               "print(resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss * 1024, "
                               "out.count(' ok'))",
                               kc.KCREEP, f"sub/wr_cheap_{th}.nml"], cwd=folder, capture_output=True, text=True)
        estimate = int(est.stdout.rsplit(" ", 2)[1]) if est.returncode == 0 else 0
        rss, ok_rows = (peak.stdout.split() + ["0", "0"])[:2]
        kc.check(peak.returncode == 0 and int(ok_rows) == 2 and int(rss) <= estimate <= 2.5 * int(rss),
                 f"two-shift table, {th} shift(s) at once: estimate {estimate / 1e6:.1f} MB between the peak "
                 f"{int(rss) / 1e6:.1f} MB and 2.5 times it ({ok_rows} rows ok)")
proc = subprocess.run([kc.KCREEP, "--estimate-memory", "sub/bad.nml"], cwd=folder, capture_output=True, text=True)
kc.check(proc.returncode == 2 and "shape = 'circle'" in proc.stderr, "estimate of a bad input: status 2")
kc.finish()
