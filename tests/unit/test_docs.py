"""The documents in step with the code, and readable:
  - each namelist group's variables (src/io/kcreep_nml_<group>.f90: its namelist
    statement and its <group>_variables list, which explains failed reads) agree;
  - `kcreep --help` names every group, docs/input.md every group and variable;
  - docs/architecture.md's module graph is tools/maintenance/module_graph.py's;
  - docs/output.md's summary sample is what `build/kcreep input/ellipse.nml`
    prints (the run times aside);
  - README.md has at most 150 lines; no table cell in README.md or docs/*.md
    is longer than 400 characters (sub-sections and lists instead).

usage: test_docs.py KCREEP SOURCE_DIR
"""
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
kc.check(len(groups) >= 6, f"{len(groups)} group modules read")

readme = open(os.path.join(root, "README.md")).read()
kc.check(readme.count("\n") <= 150, f"README.md: {readme.count(chr(10))} lines (at most 150)")
for path in [os.path.join(root, "README.md")] + sorted(glob.glob(os.path.join(root, "docs", "*.md"))):
    longest, where = 0, ""
    for number, line in enumerate(open(path), 1):
        if line.lstrip().startswith("|"):
            for cell in line.strip().strip("|").split("|"):
                if len(cell.strip()) > longest:
                    longest, where = len(cell.strip()), f"line {number}"
    kc.check(longest <= 400, f"{os.path.relpath(path, root)}: longest table cell {longest} characters ({where})")
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
