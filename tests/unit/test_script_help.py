"""Every script under scripts/ and scripts/slurm/ answers --help (and -h) with
its usage on standard output and exit status 0, and touches nothing: it runs
in a scratch copy of the repository (without build/, so a script that starts
building or benchmarking shows up as a change), from an empty working folder,
with TMPDIR pointing at another empty folder; afterwards every file of the
copy must be byte for byte and mtime for mtime what it was, and no file may
have appeared anywhere. The copy holds the files git tracks or would track
(without git: the tree less build/ and studies/), so that what other work
writes in the working tree (tables, traction files) stays out of it.

    test_script_help.py REPOSITORY_ROOT
"""
import hashlib
import os
import re
import shutil
import signal
import stat
import subprocess
import sys
import tempfile

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


def scripts_of(repo):
    found = []
    for sub in ("scripts", os.path.join("scripts", "slurm")):
        for name in sorted(os.listdir(os.path.join(repo, sub))):
            if name.endswith((".sh", ".py")):
                found.append(os.path.join(sub, name))
    return found


def command_for(copy, rel):
    path = os.path.join(copy, rel)
    if rel.endswith(".py"):
        return ["/usr/bin/python3" if os.path.exists("/usr/bin/python3") else sys.executable, path]
    return ["bash", path]


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: test_script_help.py REPOSITORY_ROOT")
    repo = os.path.abspath(sys.argv[1])
    scratch = tempfile.mkdtemp(prefix="kcreep-test-help-")
    kctest.SCRATCH = scratch
    copy = os.path.join(scratch, "repo")
    kctest.copy_repository(repo, copy)
    scripts = scripts_of(copy)
    kctest.check(len(scripts) >= 20, f"found {len(scripts)} scripts under scripts/ and scripts/slurm/")
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
                       KCREEP=os.path.join(scratch, "no-such-kcreep"))
            # its own session, so that a script that starts work (a build, a
            # benchmark) is stopped with all its children when it times out
            proc = subprocess.Popen(command_for(copy, rel) + [flag], cwd=cwd, env=env, text=True,
                                    stdout=subprocess.PIPE, stderr=subprocess.PIPE, start_new_session=True)
            try:
                out, err = proc.communicate(timeout=60)
                rc = proc.returncode
            except subprocess.TimeoutExpired:
                os.killpg(proc.pid, signal.SIGKILL)
                out, err = proc.communicate()
                rc = "timeout"
            after = snapshot(copy)
            what = f"{rel} {flag}"
            kctest.check(rc == 0, f"{what}: exit status {rc} (stderr: {err.strip()[:200]!r})")
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
