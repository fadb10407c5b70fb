#!/usr/bin/env python3
"""Fingerprints of kcreep cases, for scripts/run_cases.sh's skip rule: a case
is done only while nothing it reads has changed since its table was made.

    scripts/case_stamps.py KCREEP < NAMELISTS    one fingerprint per line
    scripts/case_stamps.py --inputs NAMELIST     the files that case reads
    scripts/case_stamps.py --help                this text

NAMELISTS: one namelist path per line on standard input. The fingerprint of
a case is the SHA-256 over the contents of the kcreep binary, the namelist
and every file the namelist names for reading: mask_file, contact_file,
gap_file, contact_inp, pressure_input_file and
the CONTACT element files <contact_file without .out>.NNNN.mat beside it
(all of them, whichever case is chosen). Relative names are taken from the
namelist's folder, as kcreep does. A file that is missing counts as
'missing'. Contents, not modification times, decide: a file rewritten with
an old mtime, or restored from a backup, still counts as changed.
Standard-library Python only.
"""
import glob
import hashlib
import os
import sys

INPUT_VARIABLES = ("mask_file", "contact_file", "gap_file", "contact_inp", "pressure_input_file")


def string_assignments(text):
    """(lower-case name, value) of every `name = 'string'` in a namelist text
    (quotes ' or ", a doubled quote inside stands for one; ! starts a comment)."""
    found = []
    i, n = 0, len(text)
    last_name = None
    while i < n:
        c = text[i]
        if c == "!":
            while i < n and text[i] != "\n":
                i += 1
        elif c in "'\"":
            value = []
            i += 1
            while i < n:
                if text[i] == c:
                    if i + 1 < n and text[i + 1] == c:
                        value.append(c)
                        i += 2
                        continue
                    break
                value.append(text[i])
                i += 1
            if last_name is not None:
                found.append((last_name, "".join(value)))
            last_name = None
            i += 1
        elif c.isalpha() or c == "_":
            j = i
            while j < n and (text[j].isalnum() or text[j] == "_"):
                j += 1
            word = text[i:j].lower()
            k = j
            while k < n and text[k] in " \t\r\n":
                k += 1
            if k < n and text[k] == "=":
                last_name = word
                i = k + 1
            else:
                last_name = None
                i = j
        else:
            if c not in " \t\r\n":
                last_name = None
            i += 1
    return found


def inputs_of(nml):
    """The files the namelist at path nml reads besides itself, in a fixed order."""
    try:
        with open(nml, encoding="latin-1") as f:
            text = f.read()
    except OSError:
        return []
    folder = os.path.dirname(os.path.abspath(nml))
    files = []
    for name, value in string_assignments(text):
        value = value.strip()
        if name not in INPUT_VARIABLES or not value:
            continue
        path = value if os.path.isabs(value) else os.path.join(folder, value)
        files.append(path)
        if name == "contact_file":
            base = path[:-4] if path.endswith(".out") else path
            files.extend(sorted(glob.glob(glob.escape(base) + ".[0-9][0-9][0-9][0-9].mat")))
    return files


def add_file(digest, path, name=True):
    if name:
        digest.update(path.encode("utf-8", "surrogateescape") + b"\0")
    try:
        with open(path, "rb") as f:
            for block in iter(lambda: f.read(1 << 20), b""):
                digest.update(block)
        digest.update(b"\0ok\0")
    except OSError:
        digest.update(b"\0missing\0")


def main():
    args = sys.argv[1:]
    if any(a in ("-h", "--help") for a in args):
        print(__doc__.strip())
        return 0
    if len(args) == 2 and args[0] == "--inputs":
        for path in inputs_of(args[1]):
            print(path)
        return 0
    if len(args) != 1 or args[0].startswith("-"):
        print("usage: case_stamps.py KCREEP < NAMELISTS | --inputs NAMELIST (see --help)", file=sys.stderr)
        return 2
    binary = hashlib.sha256()
    add_file(binary, args[0], name=False)
    for line in sys.stdin:
        nml = line.rstrip("\n")
        digest = binary.copy()
        for path in [nml] + inputs_of(nml):
            add_file(digest, path)
        print(digest.hexdigest())
    return 0


if __name__ == "__main__":
    sys.exit(main())
