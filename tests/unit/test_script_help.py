"""The rules of scripts/ (and its folders bench/, convergence/, figures/, slurm/)
and of the maintenance tools in tools/maintenance/:

- every script is executable (git mode 100755, or the execute bit without git)
  and starts with a #! line, so that it runs as itself;
- run as itself with --help (and -h) it prints its usage on standard output
  and exits 0, within HELP_SECONDS, without importing numpy, scipy or
  matplotlib (they are made to fail on import: a script imports them after
  its arguments are read), and touches nothing: it runs in a scratch copy of
  the repository (without build/, so a script that starts building or
  benchmarking shows up as a change), from an empty working folder, with
  TMPDIR pointing at another empty folder; afterwards every file of the copy
  must be byte for byte and mtime for mtime what it was, and no file may have
  appeared anywhere. The copy holds the files git tracks or would track
  (without git: the tree less build/ and the top studies/);
- every Python module a script imports is the standard library's, another
  script's, the kcreep package's, or comes from a Debian package that
  scripts/setup.sh installs (DEBIAN_PACKAGE).

    test_script_help.py REPOSITORY_ROOT
"""
import ast
import hashlib
import os
import re
import shutil
import signal
import stat
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import kctest  # noqa: E402

# A usage text is the script's own description, not its code: none of its
# lines may look like a shell or Python statement.
CODE_LINE = re.compile(r"^\s*(set -[euo]|source |here=|[A-Za-z_]+=\$\(|import |from \S+ import|def |"
                       r"while |for .* in .*; do|if \[\[|case \$|esac|fi$|done$|exec )")


def snapshot(root):
    """{relative path: (size, mtime_ns, sha256)} of every file and folder under root."""
    state = {}
    for folder, dirs, files in os.walk(root):
        for name in dirs + files:
            path = os.path.join(folder, name)
            rel = os.path.relpath(path, root)
            st = os.lstat(path)
            if stat.S_ISREG(st.st_mode):
                with open(path, "rb") as f:
                    digest = hashlib.sha256(f.read()).hexdigest()
                state[rel] = (st.st_size, st.st_mtime_ns, digest)
            else:
                state[rel] = ("dir" if stat.S_ISDIR(st.st_mode) else "other", st.st_mtime_ns, "")
    return state


HELP_SECONDS = 5
HEAVY = ("numpy", "scipy", "matplotlib")
#: the Debian package that provides each importable module outside the standard library
DEBIAN_PACKAGE = {"numpy": "python3-numpy", "scipy": "python3-scipy", "matplotlib": "python3-matplotlib"}


def scripts_of(repo):
    found = []
    for top in ("scripts", os.path.join("tools", "maintenance")):
        for folder, dirs, files in os.walk(os.path.join(repo, top)):
            dirs[:] = sorted(d for d in dirs if d != "__pycache__")
            found += [os.path.relpath(os.path.join(folder, n), repo) for n in sorted(files) if n.endswith((".sh", ".py"))]
    return found


def git_modes(repo):
    """{path: mode} of the files git tracks under scripts/ and tools/maintenance/ ({} without git)."""
    try:
        out = subprocess.run(["git", "-C", repo, "ls-files", "-s", "scripts", "tools/maintenance"], capture_output=True, text=True,
                             check=True).stdout
    except (OSError, subprocess.CalledProcessError):
        return {}
    return {line.split("\t", 1)[1]: line.split()[0] for line in out.splitlines()}


def setup_packages(repo):
    """The Debian packages scripts/setup.sh installs (its packages=(...) line)."""
    with open(os.path.join(repo, "scripts", "setup.sh")) as f:
        for line in f:
            if line.startswith("packages=("):
                return set(line[len("packages=("):line.index(")")].split())
    return set()


def imported_modules(path):
    with open(path) as f:
        tree = ast.parse(f.read(), path)
    found = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            found |= {a.name.split(".")[0] for a in node.names}
        elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
            found.add(node.module.split(".")[0])
    return found


def blocker(folder):
    """A folder whose numpy, scipy and matplotlib fail on import (first on PYTHONPATH)."""
    for name in HEAVY:
        os.makedirs(os.path.join(folder, name))
        with open(os.path.join(folder, name, "__init__.py"), "w") as f:
            f.write(f"raise ImportError('{name} imported (a script imports it only after reading its arguments)')\n")


def check_rules(repo, scripts):
    """Execute bit, #! line and dependencies of every script (in the repository itself)."""
    modes = git_modes(repo)
    packages = setup_packages(repo)
    kctest.check("python3-numpy" in packages, f"scripts/setup.sh's package list read ({len(packages)} packages)")
    local = {os.path.splitext(os.path.basename(rel))[0] for rel in scripts} | {"kcreep", "kctest"}
    for rel in scripts:
        path = os.path.join(repo, rel)
        mode = modes.get(rel)
        executable = mode == "100755" if modes else os.access(path, os.X_OK)
        kctest.check(executable, f"{rel}: executable ({'git mode ' + str(mode) if modes else 'execute bit'}; "
                                 f"git add --chmod=+x {rel})")
        with open(path) as f:
            first = f.readline()
        kctest.check(first.startswith("#!"), f"{rel}: starts with a #! line ({first.strip()[:40]!r})")
        if rel.endswith(".py"):
            for module in sorted(imported_modules(path) - set(sys.stdlib_module_names) - local):
                need = DEBIAN_PACKAGE.get(module)
                kctest.check(need in packages, f"{rel}: imports {module}, which scripts/setup.sh installs "
                                               f"({need or 'no Debian package known'})")


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: test_script_help.py REPOSITORY_ROOT")
    repo = os.path.abspath(sys.argv[1])
    scratch = tempfile.mkdtemp(prefix="kcreep-test-help-")
    kctest.SCRATCH = scratch
    copy = os.path.join(scratch, "repo")
    kctest.copy_repository(repo, copy)
    scripts = scripts_of(copy)
    kctest.check(len(scripts) >= 40, f"found {len(scripts)} scripts under scripts/ and tools/maintenance/")
    check_rules(repo, [rel for rel in scripts_of(repo)])
    heavy = os.path.join(scratch, "heavy")
    blocker(heavy)
    for rel in scripts:
        name = os.path.basename(rel)
        for flag in ("--help", "-h"):
            cwd = os.path.join(scratch, "cwd")
            tmp = os.path.join(scratch, "tmp")
            for d in (cwd, tmp):
                shutil.rmtree(d, ignore_errors=True)
                os.mkdir(d)
            before = snapshot(copy)
            env = dict(os.environ, TMPDIR=tmp, PYTHONDONTWRITEBYTECODE="1",
                       KCREEP=os.path.join(scratch, "no-such-kcreep"),
                       PYTHONPATH=os.pathsep.join([heavy] + [p for p in [os.environ.get("PYTHONPATH")] if p]))
            # its own session, so that a script that starts work (a build, a
            # benchmark) is stopped with all its children when it times out
            started = time.monotonic()
            proc = subprocess.Popen([os.path.join(copy, rel), flag], cwd=cwd, env=env, text=True,
                                    stdout=subprocess.PIPE, stderr=subprocess.PIPE, start_new_session=True)
            try:
                out, err = proc.communicate(timeout=60)
                rc = proc.returncode
                seconds = time.monotonic() - started
            except subprocess.TimeoutExpired:
                os.killpg(proc.pid, signal.SIGKILL)
                out, err = proc.communicate()
                rc, seconds = "timeout", 60.0
            after = snapshot(copy)
            what = f"{rel} {flag}"
            kctest.check(rc == 0, f"{what}: exit status {rc} (stderr: {err.strip()[-300:]!r})")
            kctest.check(seconds < HELP_SECONDS, f"{what}: answers in {seconds:.2f} s (< {HELP_SECONDS} s)")
            lines = [l for l in out.splitlines() if l.strip()]
            kctest.check(len(lines) >= 2 and name in out,
                         f"{what}: usage on standard output naming {name} ({len(lines)} lines)")
            code = [l for l in lines if CODE_LINE.search(l)]
            kctest.check(not code, f"{what}: no code lines in the usage text {code[:2]}")
            changed = sorted(k for k in set(before) | set(after) if before.get(k) != after.get(k))
            kctest.check(not changed, f"{what}: the repository copy is unchanged {changed[:5]}")
            kctest.check(not os.listdir(cwd) and not os.listdir(tmp),
                         f"{what}: nothing written in the working folder or TMPDIR "
                         f"{os.listdir(cwd)[:3] + os.listdir(tmp)[:3]}")
            if changed:  # the next script must start from the original tree
                shutil.rmtree(copy)
                kctest.copy_repository(repo, copy)
    kctest.finish()


if __name__ == "__main__":
    main()
