"""Every example in input/ runs as the README says (from a folder holding
input/, with shared/ beside it) and ends with exit 0 and either verdict ok
(every error estimate within its target: target_error, 3 times it for C23)
or verdict uncertain (some estimate above it, or a warning that says why the
estimate is not trusted); CONTACT's grid has no target.
Running them leaves nothing untracked in the repository: input/ is as it was
(no example writes beside itself) and whatever they write in the working
folder is ignored by the repository's .gitignore."""
import glob
import hashlib
import math
import re
import os
import shutil
import subprocess
import sys
import kctest as kc

scratch = kc.setup()
inputs, shared = kc.copy_inputs(scratch)
work = os.path.dirname(inputs)
examples = sorted(glob.glob(os.path.join(inputs, "*.nml")))


def state(folder):
    """{relative path: sha256} of the files under folder."""
    found = {}
    for root, _, files in os.walk(folder):
        for name in files:
            with open(os.path.join(root, name), "rb") as f:
                found[os.path.relpath(os.path.join(root, name), folder)] = hashlib.sha256(f.read()).hexdigest()
    return found


inputs_before, work_before = state(inputs), set(os.listdir(work))
kc.check(len(examples) >= 4, f"{len(examples)} examples in input/")
for path in examples:
    rel = os.path.relpath(path, work)
    if "contact" in rel and not shared:
        kc.check(False, f"{rel}: needs ../shared/contact-samples beside the repository")
        continue
    proc = subprocess.run([kc.KCREEP, rel], cwd=work, capture_output=True, text=True)
    kc.check(proc.returncode == 0, f"{rel}: exit {proc.returncode} {proc.stderr.strip()[:200]}")
    text = open(path).read().replace(" ", "").lower()
    # a &wheel_rail example writes its contact table (.wr), one row per shift and patch
    wheel_rail = "&wheel_rail" in text
    table = os.path.join(work, os.path.basename(path)[:-4] + (".wr" if wheel_rail else ".tab"))
    if proc.returncode == 0:
        rows = kc.read_table(table)
        if not wheel_rail:
            # the header states the units whole (a fixed-length header line once cut it short)
            units = [l for l in open(table) if l.startswith("# units:")]
            kc.check(len(units) == 1 and units[0].rstrip().endswith("dimensionless"),
                     f"{rel}: the table's header states its units ({units})")
        kc.check(len(rows) >= 1, f"{rel}: {len(rows)} rows")
        for row in rows if wheel_rail else rows[:1]:
            # CONTACT's grid, the normal problem read from CONTACT's input and an
            # example that sets target_error = 0 are solved as given (target 0)
            target = 0.0 if ("contact" in rel or "contact_inp=" in text or
                             re.search(r"target_error=0(\.0*)?(e[+-]?\d+)?[,/\s]", text)) else 1e-3
            errs = [row["err11"], row["err22"], row["err23"]]
            kc.check(all(math.isfinite(e) for e in errs), f"{rel}: error estimates {errs}")
            above = target > 0 and any(e > t for e, t in zip(errs, [target, target, 3 * target]))
            if not above:
                # uncertain within its estimates only with a warning that says why
                # (e.g. levels scaled below the calibrated range by the cell budget)
                where = f"shift {row['shift']:.1f} patch {int(row['patch'])}: " if wheel_rail else ""
                above = any(f"warning: {where}uncertain: " in line and "estimated relative errors" not in line
                            for line in proc.stderr.splitlines())
            kc.check(row["verdict"] == ("uncertain" if above else "ok"),
                     f"{rel}: verdict {row['verdict']} with estimates {errs} and target {target}")

def pieces(mask_path):
    """The number of 4-connected pieces of the contact area in a mask file."""
    with open(mask_path) as f:
        rows = [line.strip() for line in f.readlines()[1:] if line.strip()]
    cells = {(i, j) for j, row in enumerate(rows) for i, c in enumerate(row) if c == "1"}
    count = 0
    while cells:
        count += 1
        todo = [cells.pop()]
        while todo:
            i, j = todo.pop()
            for n in ((i + 1, j), (i - 1, j), (i, j + 1), (i, j - 1)):
                if n in cells:
                    cells.remove(n)
                    todo.append(n)
    return count


# What an example promises of its contact area holds (defect 9 of issue 31:
# wheel_rail.nml promised a two-lobed patch and the normal problem gave two).
promise = os.path.join(scratch, "promise")
os.makedirs(promise)
for name in ("wheel_rail",):
    with open(os.path.join(inputs, name + ".nml")) as f:
        text = f.read()
    comment = " ".join(l[1:].strip() for l in text.splitlines() if l.startswith("!")).lower()
    for extra in ("gap",):
        shutil.copy(os.path.join(inputs, f"{name}.{extra}"), promise)
    with open(os.path.join(promise, name + ".nml"), "w") as f:
        f.write(text + "&output contact_mask_file = 'area.mask' /\n")
    proc = subprocess.run([kc.KCREEP, name + ".nml"], cwd=promise, capture_output=True, text=True)
    found = pieces(os.path.join(promise, "area.mask")) if proc.returncode == 0 else -1
    says = 2 if "two separate" in comment else 1 if "two-lobed" in comment else None
    kc.check(says is not None and found == says,
             f"{name}.nml says its contact area is in {says} piece(s): the normal problem gives {found}")

changed = sorted(k for k in set(inputs_before) | set(state(inputs)) if inputs_before.get(k) != state(inputs).get(k))
kc.check(not changed, f"the examples write nothing into input/ (written or changed there: {changed[:6]})")
written = sorted(set(os.listdir(work)) - work_before)
kc.check(len(written) >= len(examples) - 1, f"the examples wrote their outputs in the working folder ({len(written)})")
ignored = subprocess.run(["git", "-C", kc.REPO, "check-ignore", "--no-index", "--stdin"], input="\n".join(written),
                         capture_output=True, text=True)
if ignored.returncode in (0, 1):
    kept = sorted(set(written) - set(ignored.stdout.split()))
    kc.check(not kept, f"the repository's .gitignore covers every output of the examples (not: {kept[:6]})")
kc.finish()
