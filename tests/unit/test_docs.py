"""The documents in step with the code, and readable:
  - each namelist group's variables (src/io/kcreep_nml_<group>.f90: its namelist
    statement and its <group>_variables list, which explains failed reads) agree;
  - `kcreep --help` names every group, docs/input.md every group and variable;
  - docs/architecture.md's module graph is tools/maintenance/module_graph.py's;
  - docs/output.md's summary sample is what `build/kcreep input/ellipse.nml`
    prints (the run times aside);
  - docs/input.md's opening names every group, its "Relative file names"
    every file-name variable;
  - README.md's namelist example, run as written, ends ok (what it claims);
  - README.md has at most 150 lines; no table cell in README.md or docs/*.md
    is longer than 400 characters (sub-sections and lists instead); no page
    of docs/ has more than 400 lines;
  - every relative link and #anchor in README.md and docs/*.md resolves;
  - a citation of a page's section in the docs, sources, tests, scripts and
    tools names its heading (`page.md, "Heading"`, `page.md#anchor`), and
    that heading exists; a section number after a page's name fails;
  - every path of the repository they name (src/, app/, tests/, scripts/,
    tools/, docs/, python/, lab/, with a file name) exists;
  - every file in docs/data and docs/figures is used by a page, a test, a
    source, a script or a tool (lab/ does not count);
  - docs/architecture.md names every folder of the repository.

usage: test_docs.py KCREEP SOURCE_DIR
"""
import fnmatch
import glob
import os
import re
import shutil
import subprocess
import sys

import kctest as kc

kc.setup()
root = os.path.abspath(sys.argv[2])
help_text = subprocess.run([kc.KCREEP, "--help"], capture_output=True, text=True).stdout
input_md = open(os.path.join(root, "docs", "input.md")).read()

groups = sorted(glob.glob(os.path.join(root, "src", "io", "kcreep_nml_*.f90")))
for path in groups:
    text = open(path).read()
    code = re.sub(r"!.*", "", text).replace("&\n", " ")
    statement = re.search(r"namelist\s*/(\w+)/([^\n]*)", code)
    if not statement:
        continue                                    # kcreep_nml_config: no group
    group = statement.group(1)
    read = [v.strip() for v in statement.group(2).split(",")]
    listed = re.search(group + r"_variables\(\d+\)\s*=\s*\[[^:]*::(.*?)\]", code, re.S)
    listed = [e.split()[0] for e in re.findall(r"'([^']*)'", listed.group(1))] if listed else []
    kc.check(sorted(read) == sorted(listed),
             f"&{group}: {group}_variables lists the namelist's variables ({sorted(set(read) ^ set(listed))} differ)")
    kc.check(f"&{group}" in help_text, f"kcreep --help names &{group}")
    kc.check(f"&{group}" in input_md, f"docs/input.md describes &{group}")
    missing = [v for v in read if not re.search(r"\b" + v + r"\b", input_md)]
    kc.check(not missing, f"docs/input.md names every variable of &{group} (missing: {missing})")
    # (issue 45: the opening said four groups, the file names lacked wheel_file, rail_file, ...)
    opening = re.search(r"The file holds(.*?)\n\n", input_md, re.S)
    opening = opening.group(1) if opening else ""
    kc.check(f"`&{group}`" in opening, f"docs/input.md's opening names &{group}")
    relative = input_md.split("## Relative file names")[-1].split("## ")[0]
    names = [v for v in listed if re.fullmatch(r"\w+_(file|inp)", v)]
    missing = [v for v in names if f"`{v}`" not in relative]
    kc.check(not missing, f"docs/input.md's relative file names list &{group}'s (missing: {missing})")
kc.check(len(groups) >= 6, f"{len(groups)} group modules read")

readme = open(os.path.join(root, "README.md")).read()
kc.check(readme.count("\n") <= 150, f"README.md: {readme.count(chr(10))} lines (at most 150)")
# README's namelist example runs as written and shows what it claims: ok, with an
# estimate (issue 45: its 60 x 40 grid ended uncertain at the default target)
example = re.search(r"```\n(&patch.*?)```", readme, re.S)
scratch = os.path.join(kc.SCRATCH, "readme")
os.makedirs(scratch)
with open(os.path.join(scratch, "ellipse_6x4.nml"), "w") as f:
    f.write(example.group(1) if example else "")
proc = subprocess.run([kc.KCREEP, "ellipse_6x4.nml"], cwd=scratch, capture_output=True, text=True)
claim = re.search(r"build/kcreep ellipse_6x4.nml\s+# the lines above: (\w+)", readme)
kc.check(example is not None and claim is not None and proc.returncode == 0
         and f"verdict: {claim.group(1)} " in proc.stdout and claim.group(1) == "ok",
         f"README.md's namelist example ends as the README says ({proc.stdout.strip()[-200:]!r})")
for path in [os.path.join(root, "README.md")] + sorted(glob.glob(os.path.join(root, "docs", "*.md"))):
    longest, where = 0, ""
    for number, line in enumerate(open(path), 1):
        if line.lstrip().startswith("|"):
            for cell in line.strip().strip("|").split("|"):
                if len(cell.strip()) > longest:
                    longest, where = len(cell.strip()), f"line {number}"
    kc.check(longest <= 400, f"{os.path.relpath(path, root)}: longest table cell {longest} characters ({where})")
MAX_PAGE_LINES = 400
for path in sorted(glob.glob(os.path.join(root, "docs", "*.md"))):
    n_lines = open(path).read().count("\n")
    kc.check(n_lines <= MAX_PAGE_LINES, f"{os.path.relpath(path, root)}: {n_lines} lines (at most {MAX_PAGE_LINES})")


def slug(heading):
    """GitHub's anchor of a heading: lower case, punctuation out, spaces to hyphens."""
    return re.sub(r"[^\w\- ]", "", heading.strip().lower()).replace(" ", "-")


def markdown(path):
    """(headings, text outside fenced code) of a markdown file."""
    heads, lines, fence = [], [], False
    for line in open(path):
        if line.lstrip().startswith("```"):
            fence = not fence
            lines.append("\n")
            continue
        if fence:
            lines.append("\n")
            continue
        heading = re.match(r"#{1,6}\s+(.*?)\s*#*\s*$", line)
        if heading:
            heads.append(heading.group(1))
        lines.append(line)
    return heads, "".join(lines)


def anchors(heads):
    seen, out = {}, set()
    for h in heads:
        s = slug(h)
        out.add(s if s not in seen else f"{s}-{seen[s]}")
        seen[s] = seen.get(s, 0) + 1
    return out


def cites_heading(heads, name):
    """Whether name is a heading (without its number), or its start before ' (' or ':'."""
    for h in heads:
        plain = re.sub(r"^\d+(\.\d+)*\.?\s+", "", h.replace("`", "").strip())
        if name in (plain, h) or plain.startswith(name + " (") or plain.startswith(name + ":"):
            return True
    return False


pages = [os.path.join(root, "README.md")] + sorted(glob.glob(os.path.join(root, "docs", "*.md")))
parsed = {p: markdown(p) for p in pages}
# every relative link and #anchor resolves
links = 0
for page in pages:
    text = re.sub(r"`[^`\n]*`", "", parsed[page][1])
    for m in re.finditer(r"!?\[[^\]]*\]\(([^)\s]+)(?:\s+\"[^\"]*\")?\)", text):
        target = m.group(1)
        if re.match(r"[a-z]+:", target):
            continue
        links += 1
        path, _, anchor = target.partition("#")
        dest = os.path.normpath(os.path.join(os.path.dirname(page), path)) if path else page
        where = f"{os.path.relpath(page, root)}: link {target}"
        kc.check(os.path.exists(dest), f"{where}: {os.path.relpath(dest, root)} exists")
        if anchor and os.path.exists(dest):
            if dest not in parsed:
                parsed[dest] = markdown(dest) if dest.endswith(".md") else ([], "")
            kc.check(anchor in anchors(parsed[dest][0]), f"{where}: a heading with that anchor")
kc.check(links > 50, f"{links} relative links read")

# citations of sections: by heading, and the heading exists
tracked = subprocess.run(["git", "-C", root, "ls-files"], capture_output=True, text=True).stdout.split()
if not tracked:   # a source archive: the tree itself
    tracked = [os.path.relpath(os.path.join(d, n), root) for d, _, ns in os.walk(root) for n in ns]
CODE = (".md", ".f90", ".py", ".sh", ".c", ".h", ".txt", ".in", ".cmake")
sources = [f for f in tracked if f.endswith(CODE) and not f.startswith(("lab/", "build"))
           and os.path.isfile(os.path.join(root, f))]
sources += [f for f in tracked if f.startswith("docs/data/") and f.endswith((".dat", ".txt", ".md"))]
NUMBERED = re.compile(r"\b[\w-]+\.md\)?,?\s+(?:sections?\s+|§\s*)?\d+(?:\.\d+)*\b")
QUOTED = re.compile(r"\b([\w-]+\.md),?\s+(?:section\s+)?\\?\"([^\"\\]+)\\?\"")
ANCHORED = re.compile(r"\b([\w-]+\.md)#([\w-]+)")
PATH = re.compile(r"(?<![\w./-])((?:src|app|tests|scripts|tools|docs|python|lab)/[\w./-]*\.(?:f90|py|sh|c|h|md|dat|png|txt|csv|in))\b")
texts = {}
citations = 0
for rel in sources:
    text = open(os.path.join(root, rel), errors="replace").read()
    texts[rel] = text
    flat = re.sub(r"\n\s*(?:!>|!|#|//|\*)?\s*", " ", text)   # comments joined across lines
    numbered = NUMBERED.findall(flat)
    kc.check(not numbered, f"{rel}: cites sections by heading, not number {numbered[:3]}")
    for m in QUOTED.finditer(flat):
        page = os.path.join(root, "docs", m.group(1)) if m.group(1) != "README.md" else os.path.join(root, "README.md")
        if not os.path.exists(page):
            continue
        if page not in parsed:
            parsed[page] = markdown(page)
        citations += 1
        kc.check(cites_heading(parsed[page][0], m.group(2)),
                 f'{rel}: cites {m.group(1)}, "{m.group(2)}": a heading of that page')
    if not rel.endswith(".md"):
        for m in ANCHORED.finditer(flat):
            page = os.path.join(root, "docs", m.group(1))
            if os.path.exists(page):
                parsed.setdefault(page, markdown(page))
                kc.check(m.group(2) in anchors(parsed[page][0]), f"{rel}: {m.group(0)}: a heading with that anchor")
    missing = sorted({p for p in PATH.findall(text) if not re.search(r"/[A-Z_]+\.", p)
                      and not os.path.exists(os.path.join(root, p))})
    kc.check(not missing, f"{rel}: names paths that exist (missing: {missing[:4]})")
kc.check(citations > 50, f"{citations} citations of sections by heading read")

# every file in docs/data and docs/figures is used outside lab/ (a name or a glob)
corpus = "\n".join(text for rel, text in texts.items() if not rel.startswith("docs/data/"))
globs = set(re.findall(r"[\w-]{3,}\*[\w.*-]*", corpus))
for folder in ("data", "figures"):
    for name in sorted(os.listdir(os.path.join(root, "docs", folder))):
        used = name in corpus or any(fnmatch.fnmatch(name, g) for g in globs)
        kc.check(used, f"docs/{folder}/{name}: used by a page, a test, a source or a tool (else: lab/ or delete)")

# docs/architecture.md is the layout page: it names every folder of the repository (lab/'s own aside)
architecture_text = open(os.path.join(root, "docs", "architecture.md")).read()
folders = sorted({os.path.dirname(f) for f in tracked if "/" in f and not f.startswith("lab/")})
unnamed = [d for d in folders if f"`{d}/`" not in architecture_text and f"`{d}/" not in architecture_text]
kc.check(len(folders) > 15 and not unnamed, f"docs/architecture.md names every folder ({len(folders)}; missing: {unnamed})")

# docs/architecture.md's module graph is the one the sources draw
graph = subprocess.run([sys.executable, os.path.join(root, "tools", "maintenance", "module_graph.py")], capture_output=True,
                       text=True).stdout
architecture = open(os.path.join(root, "docs", "architecture.md")).read()
kc.check(len(graph) > 1000 and graph in architecture,
         "docs/architecture.md holds tools/maintenance/module_graph.py's graph (rerun it after changing a use statement)")
# docs/output.md's sample summary is the default example's, run as the README says
scratch = os.path.join(kc.SCRATCH, "summary")
os.makedirs(os.path.join(scratch, "input"))
shutil.copy(os.path.join(root, "input", "ellipse.nml"), os.path.join(scratch, "input"))
printed = subprocess.run([kc.KCREEP, "input/ellipse.nml"], cwd=scratch, capture_output=True, text=True).stdout
output_md = open(os.path.join(root, "docs", "output.md")).read()
sample = re.search(r"## The summary\n\n```\n(.*?)```", output_md, re.S)


def without_times(text):
    return [re.sub(r"(time .*\[s\]:).*", r"\1 ...", line) for line in text.splitlines()]


kc.check(sample is not None and without_times(sample.group(1)) == without_times(printed),
         "docs/output.md's summary sample is what build/kcreep input/ellipse.nml prints (run times aside):\n"
         + "\n".join(l for l in without_times(printed) if sample is None or l not in without_times(sample.group(1))))
kc.finish()
