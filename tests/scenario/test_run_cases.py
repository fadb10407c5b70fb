"""scripts/run_cases.sh skips a case only when nothing it reads has changed
since its table was made: the namelist, the mask file, the CONTACT output
(and its .mat file) and the kcreep binary, compared by content, whatever
their modification times say: its stamp is `kcreep --fingerprint` (defect 1
of issue 31: one fingerprint for --batch, run_cases.sh and SLURM). An unchanged case is still skipped (resume).
Rows are named as kcreep --batch names them (defect 6 of issue 31): a/case.nml
and b/case.nml give the rows a/case and b/case in both.

    test_run_cases.py PATH/TO/kcreep PATH/TO/run_cases.sh
"""
import os
import re
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import kctest  # noqa: E402

RUN_CASES = os.path.abspath(sys.argv[2]) if len(sys.argv) > 2 else None


def write(path, text, mtime=None):
    with open(path, "w") as f:
        f.write(text)
    if mtime is not None:
        os.utime(path, (mtime, mtime))


def mask(mx, my, cells):
    """A mask file of mx x my cells of size 0.1 whose first `cells` cells (row by row) are in."""
    rows = []
    k = 0
    for _ in range(my):
        row = ""
        for _ in range(mx):
            row += "1" if k < cells else "0"
            k += 1
        rows.append(row)
    return f"{mx} {my} 0.1 0.1 0 0\n" + "\n".join(rows) + "\n"


def run_cases(folder, kcreep):
    proc = subprocess.run(["bash", RUN_CASES, "--jobs", "1", "cases.list", "all.tab"], cwd=folder,
                          capture_output=True, text=True, env=dict(os.environ, KCREEP=kcreep))
    m = re.search(r"\((\d+) already done\)", proc.stdout)
    skipped = int(m.group(1)) if m else -1
    rows = kctest.read_table(os.path.join(folder, "all.tab")) if proc.returncode == 0 else []
    return proc.returncode, skipped, rows, proc.stdout + proc.stderr


def main():
    scratch = kctest.setup()
    if RUN_CASES is None:
        sys.exit("usage: test_run_cases.py PATH/TO/kcreep PATH/TO/run_cases.sh")
    folder = os.path.join(scratch, "study")
    os.makedirs(os.path.join(folder, "m"))
    # mask case in a sub-folder (mask file beside its namelist), an inline-mask case, an ellipse
    write(os.path.join(folder, "m", "masked.nml"),
          "&patch shape = 'mask', mask_file = 'masked.mask' /\n&solver method = 'dense', target_error = 0 /\n")
    write(os.path.join(folder, "m", "masked.mask"), mask(12, 12, 100))
    write(os.path.join(folder, "inline.nml"),
          "&patch shape = 'mask', dx = 0.1, dy = 0.1, mask_rows = '1111', '1111', '1111' /\n&solver target_error = 0 /\n")
    write(os.path.join(folder, "ellipse.nml"), "&patch mx = 12, my = 12 /\n")
    write(os.path.join(folder, "cases.list"), "m/masked.nml\ninline.nml\nellipse.nml\n")

    rc, skipped, rows, log = run_cases(folder, kctest.KCREEP)
    kctest.check(rc == 0 and len(rows) == 3, f"first run: 3 rows (exit {rc}) {log[-300:]!r}")
    kctest.check(skipped == 0, f"first run: nothing skipped ({skipped})")
    n_before = rows[0]["n"] if rows else None
    kctest.check(n_before == 100, f"first run: the mask case has 100 cells ({n_before})")

    rc, skipped, rows, log = run_cases(folder, kctest.KCREEP)
    kctest.check(rc == 0 and skipped == 3, f"second run, nothing changed: all 3 skipped ({skipped})")

    # Rewrite the mask: 80 cells. Its mtime is set back into the past, older
    # than the table: only a comparison of contents sees the change.
    old = os.path.getmtime(os.path.join(folder, "m", "masked.mask"))
    write(os.path.join(folder, "m", "masked.mask"), mask(12, 12, 80), mtime=old - 3600)
    rc, skipped, rows, log = run_cases(folder, kctest.KCREEP)
    kctest.check(rc == 0 and skipped == 2, f"mask rewritten: only the mask case runs again ({skipped} skipped)")
    n_after = rows[0]["n"] if rows else None
    kctest.check(n_after == 80, f"mask rewritten: the table has the new cell count 80 ({n_after})")
    # the one input fingerprint of kcreep --batch, run_cases.sh and the SLURM route
    printed = subprocess.run([kctest.KCREEP, "--fingerprint", os.path.join(folder, "m", "masked.nml")],
                             capture_output=True, text=True).stdout.split()
    stamp = open(os.path.join(folder, "m", "masked.tab.stamp")).read().strip()
    kctest.check(printed and stamp == printed[0],
                 f"the stamp is kcreep --fingerprint's ({stamp[:16]}, {printed[:1]})")

    # The same for a change of the namelist itself whose mtime stays old.
    nml = os.path.join(folder, "inline.nml")
    old = os.path.getmtime(nml)
    write(nml, "&patch shape = 'mask', dx = 0.1, dy = 0.1, mask_rows = '111', '111', '111' /\n&solver target_error = 0 /\n", mtime=old - 3600)
    rc, skipped, rows, log = run_cases(folder, kctest.KCREEP)
    n_inline = rows[1]["n"] if len(rows) > 1 else None
    kctest.check(rc == 0 and skipped == 2 and n_inline == 9,
                 f"namelist rewritten with an old mtime: run again, 9 cells ({skipped} skipped, n = {n_inline})")

    # A mask file that is now read from elsewhere: the namelist names another file.
    write(os.path.join(folder, "m", "other.mask"), mask(12, 12, 50))
    nml = os.path.join(folder, "m", "masked.nml")
    old = os.path.getmtime(nml)
    write(nml, "&patch shape = 'mask', MASK_FILE = \"other.mask\" /\n&solver method = 'dense', target_error = 0 /\n",
          mtime=old - 3600)
    rc, skipped, rows, log = run_cases(folder, kctest.KCREEP)
    kctest.check(rows and rows[0]["n"] == 50, f"namelist names another mask file: 50 cells "
                 f"({rows[0]['n'] if rows else None})")
    # ... and that file changes in place (same size, old mtime)
    old = os.path.getmtime(os.path.join(folder, "m", "other.mask"))
    write(os.path.join(folder, "m", "other.mask"), mask(12, 12, 51), mtime=old - 3600)
    rc, skipped, rows, log = run_cases(folder, kctest.KCREEP)
    kctest.check(rows and rows[0]["n"] == 51, f"the other mask rewritten: 51 cells "
                 f"({rows[0]['n'] if rows else None})")

    # CONTACT output: the .out and its .mat files are inputs as well.
    samples = os.path.join(kctest.REPO, "..", "shared", "contact-samples")
    sample = None
    if os.path.isdir(samples):
        for name in sorted(os.listdir(samples)):
            if name.endswith(".out") and any(f.startswith(name[:-4] + ".") and f.endswith(".mat")
                                             for f in os.listdir(samples)):
                sample = name[:-4]
                break
    kctest.check(sample is not None, f"a CONTACT sample with .mat files in {samples}")
    if sample:
        cdir = os.path.join(folder, "c")
        os.makedirs(cdir)
        for f in os.listdir(samples):
            if f.startswith(sample + "."):
                shutil.copy(os.path.join(samples, f), cdir)
        write(os.path.join(cdir, "c.nml"), f"&patch shape = 'contact', contact_file = '{sample}.out' /\n")
        write(os.path.join(folder, "cases.list"), "c/c.nml\n")
        rc, skipped, rows, log = run_cases(folder, kctest.KCREEP)
        kctest.check(rc == 0 and skipped == 0, f"CONTACT case runs ({log[-300:]!r})")
        rc, skipped, rows, log = run_cases(folder, kctest.KCREEP)
        kctest.check(rc == 0 and skipped == 1, f"CONTACT case unchanged: skipped ({skipped})")
        mat = sorted(f for f in os.listdir(cdir) if f.endswith(".mat"))[0]
        path = os.path.join(cdir, mat)
        old = os.path.getmtime(path)
        with open(path, "a") as f:
            f.write("\n")
        os.utime(path, (old - 3600, old - 3600))
        rc, skipped, rows, log = run_cases(folder, kctest.KCREEP)
        kctest.check(skipped == 0, f"CONTACT .mat file changed: run again ({skipped} skipped)")

    # A new kcreep binary makes every result stale.
    write(os.path.join(folder, "cases.list"), "ellipse.nml\n")
    rc, skipped, rows, log = run_cases(folder, kctest.KCREEP)
    kctest.check(skipped == 1, f"before the binary changes: skipped ({skipped})")
    other = os.path.join(scratch, "kcreep-copy")
    shutil.copy(kctest.KCREEP, other)
    with open(other, "ab") as f:
        f.write(b"\0")
    rc, skipped, rows, log = run_cases(folder, other)
    kctest.check(rc == 0 and skipped == 0, f"another kcreep binary: the case runs again ({skipped} skipped)")
    check_names(scratch)
    check_tables(scratch)
    kctest.finish()


def check_tables(scratch):
    """Issue 45, item 1: contact tables (&wheel_rail), with and without &fastsim
    and &rolling: each case's .wr beside its namelist, the merged table holds
    their rows led by the case's name -- the rows kcreep --batch writes -- and a
    second run skips them (before: "table (0 rows)", no merged table, exit 0)."""
    folder = os.path.join(scratch, "tables")
    os.makedirs(os.path.join(folder, "w"))
    texts = {"plain": kctest.s1002_case(), "fast": kctest.s1002_case("&fastsim " + kctest.S1002_CREEP + "\n"),
             "roll": kctest.s1002_case("&rolling " + kctest.S1002_CREEP + "\n")}
    if texts["plain"] is None:
        kctest.check(False, f"the profiles of input/s1002_uic60.nml are not at {kctest.PROFILES}")
        return
    for name, text in texts.items():
        write(os.path.join(folder, "w", name + ".nml"), text)
    write(os.path.join(folder, "cases.list"), "w/plain.nml\nw/fast.nml\nw/roll.nml\n")
    env = dict(os.environ, KCREEP=kctest.KCREEP, OMP_NUM_THREADS="1")   # (issue 45 item 2 is another's)
    run = lambda *a: subprocess.run(list(a), cwd=folder, capture_output=True, text=True, env=env)
    proc = run("bash", RUN_CASES, "--jobs", "1", "cases.list", "merged.tab")
    kctest.check(proc.returncode == 0 and "(6 rows of 3 cases)" in proc.stdout,
                 f"run_cases.sh on 3 contact tables: exit 0, 6 rows ({proc.returncode}, {proc.stdout.strip()[-120:]!r})")
    kctest.check(all(os.path.exists(os.path.join(folder, "w", f)) for f in
                     ["plain.wr", "fast.wr", "fast.creep", "roll.wr", "roll.roll"]),
                 f"each case's files beside its namelist: {sorted(os.listdir(os.path.join(folder, 'w')))}")
    batch = run(kctest.KCREEP, "--batch", "cases.list", "batch.tab")
    merged = kctest.read_table(os.path.join(folder, "merged.tab")) if os.path.exists(os.path.join(folder, "merged.tab")) else []
    batched = kctest.read_table(os.path.join(folder, "batch.tab")) if batch.returncode == 0 else []
    kctest.check(len(merged) == 6 and [r["case"] for r in merged] == ["w/plain"] * 2 + ["w/fast"] * 2 + ["w/roll"] * 2,
                 f"the merged rows led by their case's name: {[r['case'] for r in merged]}")
    kctest.check(merged == batched, "run_cases.sh merges the rows kcreep --batch writes (same columns, same values)")
    proc = run("bash", RUN_CASES, "--jobs", "1", "cases.list", "merged.tab")
    kctest.check(proc.returncode == 0 and "(3 already done)" in proc.stdout and
                 kctest.read_table(os.path.join(folder, "merged.tab")) == merged,
                 f"second run: all 3 skipped, the same table ({proc.stdout.strip()[-120:]!r})")
    # one merged table holds one kind
    write(os.path.join(folder, "e.nml"), "&patch mx = 12, my = 12 /\n")
    write(os.path.join(folder, "mixed.list"), "e.nml\nw/plain.nml\n")
    proc = run("bash", RUN_CASES, "--jobs", "1", "mixed.list", "mixed.tab")
    kctest.check(proc.returncode == 2 and "one kind" in proc.stderr and not os.path.exists(os.path.join(folder, "e.tab")),
                 f"a mixed list refused before any case runs ({proc.returncode}, {proc.stderr.strip()!r})")


def check_names(scratch):
    """run_cases.sh and kcreep --batch name the rows of one list alike."""
    folder = os.path.join(scratch, "names")
    for sub, semi_b in (("a", 0.8), ("b", 0.6)):
        os.makedirs(os.path.join(folder, sub))
        write(os.path.join(folder, sub, "case.nml"),
              f"&patch semi_a = 1, semi_b = {semi_b}, mx = 12, my = 12 /\n&solver target_error = 0 /\n")
    write(os.path.join(folder, "cases.list"), "a/case.nml\n./b/case.nml\n")
    names = {}
    for how, command in (("run_cases.sh", ["bash", RUN_CASES, "--jobs", "1", "cases.list", "merged.tab"]),
                         ("--batch", [kctest.KCREEP, "--batch", "cases.list", "batch.tab"])):
        proc = subprocess.run(command, cwd=folder, capture_output=True, text=True,
                              env=dict(os.environ, KCREEP=kctest.KCREEP))
        kctest.check(proc.returncode == 0, f"{how} on a/case.nml and b/case.nml: exit 0 ({proc.stderr.strip()[:200]})")
        table = os.path.join(folder, "merged.tab" if how == "run_cases.sh" else "batch.tab")
        names[how] = [row["case"] for row in kctest.read_table(table)] if os.path.exists(table) else []
    kctest.check(names["run_cases.sh"] == ["a/case", "b/case"],
                 f"run_cases.sh names the rows a/case, b/case ({names['run_cases.sh']})")
    kctest.check(names["run_cases.sh"] == names["--batch"],
                 f"run_cases.sh and --batch name the rows alike ({names['run_cases.sh']}, {names['--batch']})")


if __name__ == "__main__":
    main()
