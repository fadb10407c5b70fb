"""Benchmark scripts each own one section of a shared Markdown page
(docs/performance.md): the text between `<!-- NAME:begin -->` and
`<!-- NAME:end -->` is replaced, or the section is appended, so that one
script's rerun leaves the others' figures as they were."""
import os


def replace_section(path, name, text):
    begin, end = f"<!-- {name}:begin -->", f"<!-- {name}:end -->"
    block = f"{begin}\n{text.rstrip()}\n{end}\n"
    old = open(path).read() if os.path.exists(path) else ""
    if begin in old and end in old:
        head, rest = old.split(begin, 1)
        tail = rest.split(end, 1)[1].lstrip("\n")
        new = head + block + ("\n" + tail if tail else "")
    else:
        new = old.rstrip() + ("\n\n" if old.strip() else "") + block
    tmp = path + ".tmp"
    with open(tmp, "w") as f:
        f.write(new)
    os.replace(tmp, path)
