"""Helpers for kcreep's scenario tests: run the program on a namelist in a
scratch folder and read its coefficient table (standard library only)."""
import math
import os
import shutil
import subprocess
import sys
import tempfile

#: the repository (tests/ is one level down)
REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(REPO, "python"))
from kcreep import table  # noqa: E402  (standard library only)

KCREEP = None
SCRATCH = None
FAILURES = []
CHECKS = [0]


def setup():
    """Take the kcreep binary from argv[1]; return the scratch folder."""
    global KCREEP, SCRATCH
    if len(sys.argv) < 2:
        sys.exit("usage: test_x.py PATH/TO/kcreep")
    KCREEP = os.path.abspath(sys.argv[1])
    SCRATCH = tempfile.mkdtemp(prefix="kcreep-test-")
    return SCRATCH


def copy_inputs(folder):
    """Copy the shipped examples (input/) to folder/repo/input, with the
    repository's ../shared linked beside them as folder/shared, so that they
    run with their relative paths and write nothing into the source tree.
    Returns (the copied input folder, whether ../shared/contact-samples is there)."""
    repo = REPO
    shared = os.path.join(repo, "..", "shared")
    inputs = os.path.join(folder, "repo", "input")
    shutil.copytree(os.path.join(repo, "input"), inputs)
    if os.path.isdir(shared):
        os.symlink(os.path.abspath(shared), os.path.join(folder, "shared"))
    return inputs, os.path.isdir(os.path.join(shared, "contact-samples"))


def copy_repository(repo, copy):
    """Copy the tracked files of repo to copy (git), or the tree without
    build*/, the top studies/ and caches (no git: a source archive)."""
    try:
        listed = subprocess.run(["git", "-C", repo, "ls-files", "-z", "--cached", "--others",
                                 "--exclude-standard"], capture_output=True, check=True).stdout
        files = [f for f in listed.decode().split("\0") if f]
    except (OSError, subprocess.CalledProcessError):
        files = []
    if not files:
        anywhere = shutil.ignore_patterns(".git", "build*", "__pycache__", "*.tab.partial")

        def ignore(folder, names):  # studies/ only at the top (lab/ is source)
            top = os.path.abspath(folder) == os.path.abspath(repo)
            return set(anywhere(folder, names)) | ({"studies"} & set(names) if top else set())
        shutil.copytree(repo, copy, symlinks=True, ignore=ignore)
        return
    for rel in files:
        source = os.path.join(repo, rel)
        os.makedirs(os.path.dirname(os.path.join(copy, rel)), exist_ok=True)
        try:
            shutil.copy2(source, os.path.join(copy, rel), follow_symlinks=False)
        except FileNotFoundError:  # deleted in the working tree since git listed it
            continue


def namelist(patch="", material="", solver="", output=""):
    """A namelist for a test of a specific discretisation: unless the solver
    string says otherwise, the grid is solved exactly as given (target_error = 0)
    with the paper's scheme (scheme = 'collocation', kcreep's default before
    error control), so the numbers the tests check do not move with kcreep's
    error-control defaults. Tests of error control set target_error themselves."""
    extra = []
    if "target_error" not in solver:
        extra.append("target_error = 0")
    if "scheme" not in solver:
        extra.append("scheme = 'collocation'")
    solver = ", ".join([x for x in [solver.strip().rstrip(",")] + extra if x])
    return f"&patch {patch} /\n&material {material} /\n&solver {solver} /\n&output {output} /\n"


#: the profiles of input/s1002_uic60.nml (../shared/profiles beside the repository)
PROFILES = os.path.abspath(os.path.join(REPO, "..", "shared", "profiles"))

#: fast settings for a wheel/rail table whose test is about routing, not accuracy:
#: two shifts (0 and 1 mm, one patch each) at target_error 1e-2 (0.2-0.5 s per shift here)
S1002_FAST = {"shift_from = -6, shift_to = 10": "shift_from = 0, shift_to = 1"}

#: the two creepage points of the issue-45 runs (&fastsim or &rolling appended to the example)
S1002_CREEP = "mu = 0.3, creepages = 0 0 0, 2e-3 0 0 /"


def s1002_case(extra="", target_error=1e-2):
    """input/s1002_uic60.nml with its profiles by absolute path, shifts 0 and 1,
    &solver target_error, and extra groups appended; None when ../shared is absent."""
    if not os.path.isdir(PROFILES):
        return None
    text = open(os.path.join(REPO, "input", "s1002_uic60.nml")).read()
    text = text.replace("'../../shared/profiles", "'" + PROFILES)
    for old, new in S1002_FAST.items():
        assert old in text, f"input/s1002_uic60.nml no longer has {old!r}"
        text = text.replace(old, new)
    return text + f"&solver target_error = {target_error:g} /\n" + extra


def run(text, folder, name="case", expect_ok=True, files=None):
    """Write text to folder/name.nml and run kcreep there.
    Returns (returncode, stdout, stderr, table or None)."""
    for fname, content in (files or {}).items():
        with open(os.path.join(folder, fname), "w") as f:
            f.write(content)
    path = os.path.join(folder, name + ".nml")
    with open(path, "w") as f:
        f.write(text)
    proc = subprocess.run([KCREEP, name + ".nml"], cwd=folder, capture_output=True, text=True)
    table_path = os.path.join(folder, name + ".tab")
    table = None
    if proc.returncode == 0 and os.path.exists(table_path):
        table = read_table(table_path)
    if expect_ok and proc.returncode != 0:
        raise RuntimeError(f"kcreep failed on {name}: {proc.stderr.strip()}")
    return proc.returncode, proc.stdout, proc.stderr, table


def circle_profile(radius, half, convex_down, step=0.25):
    """A circular profile as a two-column file's text: y from -half to half
    (mm), z = radius - sqrt(radius^2 - y^2), negated for a wheel (convex_down)."""
    rows = []
    for k in range(int(round(2 * half / step)) + 1):
        y = -half + k * step
        z = radius - math.sqrt(radius * radius - y * y)
        rows.append(f"{y:.10f} {(-z if convex_down else z):.12f}")
    return "\n".join(rows) + "\n"


def read_table(path):
    """Rows of a kcreep table as dicts (numbers as float where they parse)."""
    return table.read(path)


def coefficients(text, folder, name="case"):
    """The single table row of a successful run."""
    return run(text, folder, name)[3][0]


def parabolic(np, inside, dx, dy):
    """kcreep's pressure of a bare mask (numpy passed in: this module needs only the
    standard library): on each strip segment of half length s, p = k (s^2 - (x - x_m)^2) / s;
    Fn = 1."""
    p = np.zeros(inside.shape)
    for j, row in enumerate(inside):
        i = 0
        while i < len(row):
            if not row[i]:
                i += 1
                continue
            k = i
            while k < len(row) and row[k]:
                k += 1
            s, xm = (k - i) * dx / 2, (i + k - 1) / 2
            x = (np.arange(i, k) - xm) * dx
            p[j, i:k] = (s * s - x * x) / s
            i = k
    return p / (p.sum() * dx * dy)


def check(condition, message):
    CHECKS[0] += 1
    status = "ok  " if condition else "FAIL"
    print(f"{status} {message}")
    if not condition:
        FAILURES.append(message)


def close(value, expected, rel, message):
    err = abs(value - expected) / max(abs(expected), 1e-300)
    check(err <= rel, f"{message}: {value:.8g} vs {expected:.8g} (rel. diff {err:.2e}, allowed {rel:.1e})")


def small(value, scale, rel, message):
    check(abs(value) <= rel * abs(scale), f"{message}: |{value:.3e}| <= {rel:.0e} * {abs(scale):.3e}")


def finish():
    passed = CHECKS[0] - len(FAILURES)
    print(f"{passed} passed, {len(FAILURES)} failed")
    if FAILURES:
        print(f"scratch folder kept for inspection: {SCRATCH}")
    elif SCRATCH and not os.environ.get("KCREEP_KEEP_TEST_FILES"):
        shutil.rmtree(SCRATCH, ignore_errors=True)
    sys.exit(1 if FAILURES else 0)


def isnan(x):
    return isinstance(x, float) and math.isnan(x)


def scheme_setting(scheme, alpha):
    """&solver text for a scheme: the collocation point only where it is used
    (kcreep refuses alpha with the backward scheme)."""
    return f"scheme='{scheme}'" + (f", alpha={alpha}" if scheme == "collocation" else "")
