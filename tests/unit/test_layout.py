"""The architecture, checked on the sources: every file under src/ and app/
holds the module of its name with the kcreep_ prefix; dependencies between
pipeline stages run one way (io is used by nothing below it, app by nothing
in src/, io reaches the solver's types through the facade only); and the library prints nothing, reads no environment and calls
nothing of the operating system (the command line in app/ does that).
The laboratory is walled off: no code outside lab/ (a build step, test,
script, tool or source; comments and docstrings may point into it) names a
path in lab/, lab/README.md indexes every file in lab/, and scripts/ keeps
to at most 45 files.

usage: test_layout.py SOURCE_DIR
"""
import os
import re
import sys

import kctest as kc

root = os.path.abspath(sys.argv[1])
# stage -> stages it may use (the facade src/kcreep.f90 is stage 'facade')
allowed = {
    "core": {"core"},
    "geometry": {"core", "geometry"},
    "discretisation": {"core", "geometry", "discretisation"},
    "solve": {"core", "geometry", "discretisation", "solve"},
    "coefficients": {"core", "geometry", "discretisation", "solve", "coefficients"},
    # the refinement engine: its constants, ladders and estimate (pure; the pipeline runs the levels)
    "refine": {"core", "geometry", "discretisation", "solve", "coefficients", "refine"},
    "pipeline": {"core", "geometry", "discretisation", "solve", "coefficients", "refine", "pipeline"},
    "facade": {"core", "geometry", "discretisation", "solve", "coefficients", "refine", "pipeline"},
    # input and output read into and write from the facade's types: no solve or pipeline module
    "io": {"core", "geometry", "discretisation", "coefficients", "refine", "facade", "io"},
    # one door: the C API and the command line reach the solver through the facade only
    "api": {"core", "facade", "api"},   # the topic modules share kcreep_capi_handle
    "app": {"core", "facade", "io", "app"},
}
# single modules a stage may use beyond its stages: the C API reads the profile
# files kcreep_set_profiles names with io's reader (the program's &wheel_rail reads them so)
also_allowed = {"api": {"kcreep_profile_file"}}
stage_of, files = {}, []
for folder in ("src", "app"):
    for dirpath, _, names in os.walk(os.path.join(root, folder)):
        for name in sorted(names):
            if not name.endswith(".f90"):
                continue
            path = os.path.join(dirpath, name)
            rel = os.path.relpath(path, root)
            text = open(path).read()
            if rel == "app/main.f90":
                stage = "app"
            elif rel == "src/kcreep.f90":
                stage = "facade"
            else:
                stage = "app" if folder == "app" else rel.split(os.sep)[1]
            files.append((rel, stage, text))
            module = re.search(r"^\s*module\s+(\w+)\s*$", text, re.M | re.I)
            if module:
                stage_of[module.group(1).lower()] = stage
                kc.check(module.group(1).lower() == name[:-4] and name.startswith("kcreep"),
                         f"{rel}: module {module.group(1)} named after its file, kcreep_ prefix")
            else:
                kc.check(rel == "app/main.f90", f"{rel}: holds a module")

# no source file above 700 lines (issue 31): a longer one is split by topic
MAX_LINES = 700
for rel, stage, text in files:
    n_lines = len(text.splitlines())
    kc.check(n_lines <= MAX_LINES, f"{rel}: {n_lines} lines, at most {MAX_LINES}")

for rel, stage, text in files:
    used = {u.lower() for u in re.findall(r"^\s*use\s+(?!,)(\w+)", text, re.M | re.I)}
    for u in sorted(used):
        if u in stage_of and stage_of[u] not in allowed[stage] and u not in also_allowed.get(stage, ()):
            kc.check(False, f"{rel} ({stage}) uses {u} ({stage_of[u]}): against the pipeline direction")
    if stage not in ("app", "io"):
        code = "\n".join(line.split("!")[0] for line in text.splitlines())
        for pattern, what in ((r"\bprint\b", "print"), (r"output_unit|error_unit", "standard output/error"),
                              (r"get_environment_variable", "environment"), (r"\bopen\s*\(", "open a file"),
                              (r"execute_command_line", "a shell"), (r"/proc/", "/proc"),
                              (r"name\s*=\s*'(rename|getpid|flock|exit|getenv)'", "a POSIX call")):
            kc.check(not re.search(pattern, code, re.I), f"{rel}: no {what} in the library")
    if stage == "io":
        code = "\n".join(line.split("!")[0] for line in text.splitlines())
        kc.check(not re.search(r"action\s*=\s*'(write|readwrite)'|status\s*=\s*'(new|replace)'", code, re.I),
                 f"{rel}: io reads, it writes no files (app/ does)")
kc.check(len(files) > 30, f"{len(files)} Fortran files checked")


# ---- the laboratory: nothing outside lab/ imports, runs or reads it ----
def code_strings_py(text):
    """The string constants of a Python file other than docstrings."""
    import ast
    tree = ast.parse(text)
    docs = set()
    for node in ast.walk(tree):
        if isinstance(node, (ast.Module, ast.FunctionDef, ast.ClassDef, ast.AsyncFunctionDef)) and node.body:
            first = node.body[0]
            if isinstance(first, ast.Expr) and isinstance(first.value, ast.Constant):
                docs.add(id(first.value))
    return [n.value for n in ast.walk(tree)
            if isinstance(n, ast.Constant) and isinstance(n.value, str) and id(n) not in docs]


def code_lines(text, comment):
    """The lines of a file without their comments (comment: the comment marker)."""
    return [line.split(comment)[0] for line in text.splitlines()]


LAB_PATH = re.compile(r"(^|[\s\"'/$({=:])lab/|^lab$")
readers = []
for top in ("src", "app", "tests", "scripts", "tools", "python", "cmake", "include", "CMakeLists.txt"):
    where = os.path.join(root, top)
    paths = [where] if os.path.isfile(where) else [os.path.join(d, n) for d, _, ns in os.walk(where) for n in ns]
    for path in sorted(paths):
        rel = os.path.relpath(path, root)
        if "__pycache__" in rel or rel in (os.path.join("tests", "unit", "test_layout.py"),
                                           os.path.join("tests", "unit", "test_docs.py")):
            continue   # (this test reads lab/ for its index; the docs test names it to leave it out)
        if path.endswith(".py"):
            pieces = code_strings_py(open(path).read())
        elif path.endswith((".sh", ".txt", ".cmake")):
            pieces = code_lines(open(path).read(), "#")
        elif path.endswith((".f90", ".in")):
            pieces = code_lines(open(path).read(), "!")
        elif path.endswith((".c", ".h")):
            pieces = [re.sub(r"/\*.*?\*/|//[^\n]*", "", open(path).read(), flags=re.S)]
        else:
            continue
        if any(LAB_PATH.search(piece.strip()) for piece in pieces):
            readers.append(rel)
kc.check(not readers, f"nothing outside lab/ names a path in it (in code, not comments): {readers}")

# scripts/ holds the user's tools, not studies: a cap on its size (42 files at
# the move of the studies to lab/, 77 before) makes a new study go to lab/
scripts = [os.path.join(d, n) for d, _, ns in os.walk(os.path.join(root, "scripts")) for n in ns
           if "__pycache__" not in d]
kc.check(len(scripts) <= 45, f"scripts/ holds {len(scripts)} files (at most 45; studies go to lab/)")

# lab/README.md names every file in lab/ (its index: status and what it backs)
lab = os.path.join(root, "lab")
index = open(os.path.join(lab, "README.md")).read()
unindexed = sorted(os.path.relpath(os.path.join(d, n), lab) for d, _, ns in os.walk(lab) for n in ns
                   if n != "README.md" and "__pycache__" not in d
                   and os.path.relpath(os.path.join(d, n), lab) not in index)
kc.check(not unindexed, f"lab/README.md indexes every file in lab/ (missing: {unindexed[:8]})")
kc.finish()
