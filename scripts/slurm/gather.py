#!/usr/bin/env python3
"""Gather step of run_cases_slurm.sh: merge the chunk tables of a sweep into
one table, checking that every case of the list is present exactly once.

    scripts/slurm/gather.py WORKDIR OUT_TABLE
    scripts/slurm/gather.py --help    this text

WORKDIR holds cases.list (one absolute namelist path per line), chunk_size
and chunks/NNNNN.{list,tab,tab.partial}. Every row must stand at its place
(row j of chunk i is case (i-1)*chunk_size + j, checked by its name; in a
table of contact tables, &wheel_rail, case j has a block of rows, one per
shift and patch, each led by its name). When
all cases are present OUT_TABLE is written whole (temporary file, rename):
comments first, then the column names, then one row per case in list order.
Otherwise OUT_TABLE is left as it was, the missing cases are listed on
standard error and in WORKDIR/missing.list, and resubmitting the same
command runs just those.

Exit status: 0 all cases present and solved, 5 all present but some rows
say error:..., 1 cases missing or misplaced, 2 WORKDIR unusable.
"""
import os
import re
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "python"))
from kcreep import table  # noqa: E402  (standard library only)


case_name = table.case_name
read_chunk = table.read_chunk


def listed_name(entry, folder):
    """The table's case column as kcreep --batch writes it for a list entry:
    relative to the list's folder (an absolute path inside it made relative,
    leading './' dropped), without the extension, blanks replaced."""
    name = entry
    if folder and name.startswith(folder + "/") and len(name) > len(folder) + 1:
        name = name[len(folder) + 1:]
    while len(name) > 2 and name.startswith("./"):
        name = name[2:]
    slash, dot = name.rfind("/"), name.rfind(".")
    if dot > slash + 1:
        name = name[:dot]
    name = "".join("_" if (c == " " or ord(c) < 33) else c for c in name)
    return name or "-"


def main():
    if any(a in ("-h", "--help") for a in sys.argv[1:]):
        print(__doc__.strip())
        return 0
    if len(sys.argv) != 3:
        print("usage: gather.py WORKDIR OUT_TABLE (see --help)", file=sys.stderr)
        return 2
    workdir, out = sys.argv[1], sys.argv[2]
    try:
        cases = [l.rstrip("\n") for l in open(os.path.join(workdir, "cases.list")) if l.strip()]
        chunk_size = int(open(os.path.join(workdir, "chunk_size")).read())
    except (OSError, ValueError) as e:
        print(f"gather: error: {workdir} is not a run_cases_slurm.sh folder ({e})", file=sys.stderr)
        return 2
    n_chunks = (len(cases) + chunk_size - 1) // chunk_size
    # the chunk tables name each case by its absolute path (the chunk lists hold
    # those); the gathered table names it as kcreep --batch of the whole list
    # would: relative to the list's folder
    try:
        list_dir = open(os.path.join(workdir, "list_dir")).read().rstrip("\n")
    except OSError:
        list_dir = None
    chunks_dir = os.path.realpath(os.path.join(workdir, "chunks"))

    header, columns, per_case_comments, rows, n_gathered = None, None, [], [], 0
    missing, problems = [], []
    for i in range(1, n_chunks + 1):
        first = (i - 1) * chunk_size
        expected = cases[first:first + chunk_size]
        stem = os.path.join(workdir, "chunks", f"{i:05d}")
        if not os.path.exists(stem + ".tab"):
            done = 0
            if os.path.exists(stem + ".tab.partial"):   # cases of a killed task, kept for the resubmit
                done = sum(1 for l in open(stem + ".tab.partial") if l.startswith("# fingerprint "))
            missing += expected[done:] if done else expected
            if done:
                problems.append(f"chunk {i}: killed after {done} of {len(expected)} cases (kept in {stem}.tab.partial)")
            else:
                problems.append(f"chunk {i}: no table")
            continue
        comments, cols, chunk_rows = read_chunk(stem + ".tab")
        if columns is None:
            header = [c for c in comments if not c.startswith("# case ") and not c.startswith("# batch ")]
            columns = cols
        elif cols != columns:
            problems.append(f"chunk {i}: other columns than chunk 1")
            missing += expected
            continue
        # each case's rows: one, or a block (contact tables: their second column is shift)
        names = [r.split(None, 1)[0] for r in chunk_rows]
        blocks = [[k] for k in range(len(names))]
        if cols.split()[2:3] == ["shift"]:
            blocks = []
            for k, name in enumerate(names):
                if blocks and names[blocks[-1][0]] == name:
                    blocks[-1].append(k)
                else:
                    blocks.append([k])
        if [names[b[0]] for b in blocks] != [listed_name(p, chunks_dir) for p in expected]:
            problems.append(f"chunk {i}: rows {names} do not match its cases")
            missing += expected
            continue
        chunk_rows = [(listed_name(p, list_dir) if list_dir else case_name(p)) + chunk_rows[k][len(names[k]):]
                      for p, b in zip(expected, blocks) for k in b]
        n_gathered += len(blocks)
        for c in comments:            # per-case messages, renumbered to the place in the whole list
            m = re.match(r"# case (\d+) (.*)", c)
            if m:
                per_case_comments.append(f"# case {first + int(m.group(1))} {m.group(2)}")
        rows += chunk_rows

    if missing or n_gathered != len(cases):
        with open(os.path.join(workdir, "missing.list"), "w") as f:
            f.write("".join(p + "\n" for p in missing))
        for p in problems:
            print(f"gather: {p}", file=sys.stderr)
        print(f"gather: {len(missing)} of {len(cases)} cases missing (listed in {workdir}/missing.list):",
              file=sys.stderr)
        for p in missing:
            print(f"gather: missing {p}", file=sys.stderr)
        print(f"gather: {out} not written; resubmit the same command to run the missing cases", file=sys.stderr)
        return 1

    verdict = columns[1:].split().index("verdict")   # columns may follow it
    failed = sum(1 for r in rows if r.split()[verdict].startswith("error:"))
    lines = header + [f"# gathered from {n_chunks} SLURM array task(s): {len(cases)} cases, {failed} failed "
                      "(verdict error:...)"] + per_case_comments + [columns] + rows
    tmp = f"{out}.gather-tmp-{os.getpid()}"
    with open(tmp, "w") as f:
        f.write("".join(l + "\n" for l in lines))
    os.replace(tmp, out)
    missing_file = os.path.join(workdir, "missing.list")
    if os.path.exists(missing_file):
        os.remove(missing_file)
    print(f"gather: {len(cases)} cases, each present once, {failed} failed: {out}")
    return 5 if failed else 0


if __name__ == "__main__":
    code = main()
    if len(sys.argv) == 3 and os.path.isdir(sys.argv[1]):
        # the exit status, for run_cases_slurm.sh --wait (no accounting needed)
        with open(os.path.join(sys.argv[1], "gather.exit"), "w") as f:
            f.write(f"{code}\n")
    sys.exit(code)
