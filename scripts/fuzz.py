#!/usr/bin/env python3
"""Mutation fuzzer for kcreep's namelist and mask reader (standard library only).

Each input is a namelist (and, half the time, a mask file) made by mutating
valid seeds: random bytes flipped, inserted or deleted, truncation, numbers
replaced by huge, tiny, NaN, Inf or overflowing values, long lines,
unbalanced quotes, missing '/', duplicated or misspelt groups, control and
non-ASCII bytes, mask characters and headers changed, files replaced by a
folder or emptied.

Every input runs through the reader-only harness (check_input: read,
validate, build the patch, probe the output folder). Small valid patches
also run through kcreep itself. A run passes when it ends either with
exit 0 (check_input: one 'ok' line; kcreep: a complete table with finite
coefficients or an explained verdict) or with exactly one line
'kcreep: error: ...' on stderr and exit status 2, 3 or 4 -- never a signal,
a hang (timeout), another exit status, extra stderr lines, or a temporary
file left behind. Inputs that fail are kept in the findings folder.

  fuzz.py --check build/tests/check_input --kcreep build/kcreep --duration 30 [--seed N] [--findings DIR]
"""
import argparse
import collections
import json
import math
import os
import random
import shutil
import subprocess
import sys
import tempfile
import time

SEED_NAMELISTS = [
    "&patch shape='ellipse', semi_a=1.0, semi_b=0.5, mx=12, my=6 /\n&material g=1.0, nu=0.25 /\n"
    "&solver scheme='collocation', alpha=0.5 /\n",
    "&patch semi_a=2, semi_b=1, mx=10, my=5 /\n&material nu=0.3 /\n&solver scheme='backward', spin_shift=0.1666 /\n",
    "&patch shape='mask', mask_rows='.##.', '####', '.##.', dx=0.1, dy=0.1, x0=-0.15, y0=-0.1 /\n"
    "&material g=80e9, nu=0.28 /\n&solver load_cases='xi eta' /\n",
    "&patch shape='mask', mask_file='m.mask' /\n&material nu=0.0 /\n&solver alpha=0.9 /\n",
    "! comment line\n&patch shape = 'MASK', mask_file = 'm.mask', mx = 5, my = 4 /\n&solver load_cases = 'phi' /\n",
    "&material nu=0.5 /\n&patch mx=7, my=7 /\n",
    "&patch shape='mask', mask_rows='#', dx=1e-3, dy=1e-3 /\n",
    "&patch shape='mask', mask_rows='#.#', '.#.', '#.#', dx=1, dy=1, x0=-1, y0=-1 /\n&solver scheme='backward' /\n",
]
SEED_MASKS = [
    "5 4 0.1 0.1 -0.2 -0.15\n.###.\n#####\n#####\n.###.\n",
    "5 4 1e-3 2e-3 0 0\n! a comment\n##...\n##...\n\n..###\n..###\n",
    "3 3 1 1 -1 -1\n###\n#.#\n###",
    "1 1 0.5 0.5 0 0\n1\n",
]
NUMBERS = ["0", "-0", "1e308", "1e309", "-1e308", "1e-308", "4.9e-324", "NaN", "nan", "Inf", "-Inf", "+inf",
           "99999999999", "2147483647", "-2147483648", "2147483648", "1e-300", "0.5d0", "1.0e+3", "3*",
           "1,2", "1.5", "-1", "65536", "100000", "2000", "1.", ".5", "--1", "1e", "0x10", "T", ".true."]
TOKENS = ["/", "&", "&patch", "&end", "&material", "&solver", "&output", "'", '"', ",", "=", "!", "\n", "\t",
          "mx=", "my=", "dx=", "mask_rows=", "mask_file=", "shape='mask'", "alpha=", "nu=", "g=",
          "load_cases=", "scheme=", "semi_a=", "x0=", "#", ".", "1", "0", "\x00", "\xff", "\r\n", "é", ";",
          "mask_rows(3)=", "mask_rows(0)=", "mask_rows(99999)=", "mx(2)=", "%", "*", "2*'##'"]


def mutate(text, rng, kind):
    data = bytearray(text.encode("utf-8", "surrogateescape"))
    for _ in range(rng.choice([1, 1, 2, 3, 5, 8])):
        op = rng.randrange(12)
        pos = rng.randrange(len(data) + 1) if data else 0
        if op == 0 and data:                        # flip a byte
            data[min(pos, len(data) - 1)] = rng.randrange(256)
        elif op == 1:                               # insert a random byte
            data[pos:pos] = bytes([rng.randrange(256)])
        elif op == 2 and data:                      # delete a span
            del data[pos:pos + rng.randrange(1, 12)]
        elif op == 3:                               # truncate
            del data[pos:]
        elif op == 4:                               # replace a number
            digits = [i for i, c in enumerate(data) if chr(c).isdigit()]
            if digits:
                i = rng.choice(digits)
                j = i
                while j < len(data) and (chr(data[j]).isalnum() or chr(data[j]) in ".+-"):
                    j += 1
                data[i:j] = rng.choice(NUMBERS).encode()
        elif op == 5:                               # insert a token
            data[pos:pos] = rng.choice(TOKENS).encode("utf-8", "surrogateescape")
        elif op == 6:                               # long line
            data[pos:pos] = (rng.choice(["#", "1", "a", " ", "'", "9"]) * rng.choice([300, 3000, 70000])).encode()
        elif op == 7:                               # drop every '/' or every quote
            ch = rng.choice([b"/", b"'", b"\n"])
            data = data.replace(ch, b"", rng.choice([1, 100]))
        elif op == 8:                               # duplicate a chunk
            i = rng.randrange(len(data) + 1)
            data[pos:pos] = data[i:i + rng.randrange(1, 60)]
        elif op == 9 and kind == "mask":            # change mask characters
            for _ in range(rng.randrange(1, 4)):
                if data:
                    data[rng.randrange(len(data))] = ord(rng.choice("#.10 x\t\x00"))
        elif op == 10 and kind == "mask":           # new header
            line_end = data.find(b"\n")
            header = " ".join(rng.choice(NUMBERS + ["3", "4", "0.1", "1"]) for _ in range(rng.choice([4, 5, 6, 6, 6, 7])))
            data[:max(line_end, 0)] = header.encode()
        elif op == 11:                              # case change / whitespace
            data = bytearray(data.upper() if rng.random() < 0.5 else data.replace(b" ", b"\t"))
    return bytes(data)


def make_input(rng, folder):
    """Write case.nml (and maybe m.mask) into folder; return a short description."""
    nml = mutate(rng.choice(SEED_NAMELISTS), rng, "nml") if rng.random() < 0.85 else rng.choice(SEED_NAMELISTS).encode()
    mask_kind = rng.random()
    if mask_kind < 0.05:
        os.mkdir(os.path.join(folder, "m.mask"))                   # a folder where a file is expected
    elif mask_kind < 0.1:
        open(os.path.join(folder, "m.mask"), "wb").close()         # empty
    elif mask_kind < 0.15:
        with open(os.path.join(folder, "m.mask"), "wb") as f:      # random bytes
            f.write(os.urandom(rng.randrange(1, 400)))
    elif mask_kind < 0.6:
        with open(os.path.join(folder, "m.mask"), "wb") as f:
            f.write(mutate(rng.choice(SEED_MASKS), rng, "mask"))
    else:
        with open(os.path.join(folder, "m.mask"), "w") as f:
            f.write(rng.choice(SEED_MASKS))
    if rng.random() < 0.02:
        os.mkdir(os.path.join(folder, "case.nml"))
    else:
        with open(os.path.join(folder, "case.nml"), "wb") as f:
            f.write(nml)
    return nml


def judge(proc, what, allow_ok_line):
    """None when the run obeys the contract, else a short reason."""
    if proc is None:
        return f"{what}: timeout (hang)"
    code = proc.returncode
    err_lines = proc.stderr.decode("utf-8", "replace").strip().splitlines()
    if code < 0:
        return f"{what}: killed by signal {-code}"
    if code == 0:
        bad = [l for l in err_lines if not l.startswith("kcreep: warning: ")]
        if bad:
            return f"{what}: exit 0 with stderr {bad[:2]}"
        if allow_ok_line and not proc.stdout.startswith(b"ok "):
            return f"{what}: exit 0 without the ok line"
        return None
    if code not in (2, 3, 4):
        return f"{what}: exit status {code}"
    if len(err_lines) != 1 or not err_lines[0].startswith("kcreep: error: "):
        return f"{what}: {len(err_lines)} stderr lines: {err_lines[:3]}"
    return None


def run(cmd, folder, timeout):
    try:
        return subprocess.run(cmd, cwd=folder, capture_output=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return None


def table_problem(path):
    """A finished table has the column line and one complete row."""
    try:
        lines = open(path, errors="replace").read().splitlines()
    except OSError as e:
        return f"table unreadable: {e}"
    cols = [l for l in lines if l.startswith("# case ")]
    rows = [l for l in lines if l and not l.startswith("#")]
    if len(cols) != 1 or len(rows) != 1:
        return "table incomplete"
    names, values = cols[0][1:].split(), rows[0].split()
    if len(values) != len(names):
        return f"table row has {len(values)} fields for {len(names)} columns"
    row = dict(zip(names, values))
    for c in ("c11", "c22", "c23", "rcond", "berr"):
        try:
            v = float(row[c])
        except ValueError:
            return f"table {c} = {row[c]!r}"
        # the iterative path estimates no rcond (NaN by design); masks under
        # error control reach it whenever their splits grow past the dense limit
        iterative_rcond = c == "rcond" and float(row.get("iterations", "0")) > 0
        if math.isinf(v) or (math.isnan(v) and c in ("rcond", "berr") and not iterative_rcond):
            return f"table {c} = {row[c]} (not finite)"
    return None


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--check", required=True, help="the check_input harness")
    ap.add_argument("--kcreep", help="the kcreep binary (full runs of small valid inputs)")
    ap.add_argument("--duration", type=float, default=30, help="seconds to run [30]")
    ap.add_argument("--seed", type=int, default=None, help="random seed [time]")
    ap.add_argument("--findings", default=None, help="folder for failing inputs [none: only report]")
    ap.add_argument("--summary", default=None, help="write the summary as JSON here")
    ap.add_argument("--timeout", type=float, default=10, help="per-run timeout in seconds [10]")
    args = ap.parse_args()
    seed = args.seed if args.seed is not None else int(time.time())
    rng = random.Random(seed)
    check = os.path.abspath(args.check)
    kcreep = os.path.abspath(args.kcreep) if args.kcreep else None
    scratch = tempfile.mkdtemp(prefix="kcreep-fuzz-")
    stats = collections.Counter()
    messages = collections.Counter()
    findings = []
    start = time.monotonic()
    try:
        while time.monotonic() - start < args.duration:
            stats["inputs"] += 1
            folder = os.path.join(scratch, f"c{stats['inputs']}")
            os.mkdir(folder)
            text = make_input(rng, folder)
            proc = run([check, "case.nml"], folder, args.timeout)
            reason = judge(proc, "check_input", True)
            if proc is not None and reason is None:
                if proc.returncode == 0:
                    stats["valid"] += 1
                else:
                    stats[f"exit {proc.returncode}"] += 1
                    msg = proc.stderr.decode("utf-8", "replace").split(":", 3)[-1].strip()
                    messages[msg.split("(")[0][:60]] += 1
            full_run = False
            if reason is None and proc.returncode == 0 and kcreep:
                mx, my, n = (int(v) for v in proc.stdout.split()[1:4])
                lowered = text.lower()
                # full runs only for small patches that write nowhere but here
                full_run = n <= 400 and mx * my <= 40000 and b"_file" not in lowered.replace(b"mask_file", b"")
            if full_run:
                stats["full runs"] += 1
                proc2 = run([kcreep, "case.nml"], folder, args.timeout * 3)
                reason = judge(proc2, "kcreep", False)
                if reason is None and proc2.returncode == 0:
                    reason = table_problem(os.path.join(folder, "case.tab"))
                    verdict = proc2.stdout.decode("utf-8", "replace").split("verdict: ")[-1].split()[0]
                    stats[f"verdict {verdict}"] += 1
                elif reason is None:
                    stats[f"kcreep exit {proc2.returncode}"] += 1
                    msg = proc2.stderr.decode("utf-8", "replace").split(":", 2)[-1].strip()
                    messages["kcreep: " + msg.split("(")[0][:60]] += 1
            leftovers = [f for f in os.listdir(folder) if "kcreep-tmp" in f]
            if reason is None and leftovers:
                reason = f"temporary file left: {leftovers}"
            if reason:
                stats["findings"] += 1
                findings.append({"input": stats["inputs"], "reason": reason})
                print(f"FINDING {stats['inputs']}: {reason}", flush=True)
                if args.findings:
                    dest = os.path.join(args.findings, f"finding-{seed}-{stats['inputs']}")
                    shutil.copytree(folder, dest, symlinks=True)
                    with open(os.path.join(dest, "reason.txt"), "w") as f:
                        f.write(reason + "\n")
            shutil.rmtree(folder, ignore_errors=True)
    finally:
        shutil.rmtree(scratch, ignore_errors=True)
    elapsed = time.monotonic() - start
    summary = {"seed": seed, "seconds": round(elapsed, 1), "counts": dict(stats),
               "distinct_error_messages": len(messages), "top_errors": messages.most_common(12),
               "kcreep_errors": sorted(m for m in messages if m.startswith("kcreep: ")),
               "findings": findings[:50]}
    print(f"fuzz: seed {seed}, {stats['inputs']} inputs in {elapsed:.0f} s: {stats['valid']} valid, "
          f"{stats['full runs']} full kcreep runs, {len(messages)} distinct error messages, "
          f"{stats['findings']} findings")
    print("fuzz: counts " + ", ".join(f"{k} {v}" for k, v in sorted(stats.items())))
    if args.summary:
        with open(args.summary, "w") as f:
            json.dump(summary, f, indent=1)
    sys.exit(1 if stats["findings"] else 0)


if __name__ == "__main__":
    main()
