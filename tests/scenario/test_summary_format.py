"""Defect 5 of issue 31: the summary's numbers stay apart and in one notation.

On cases that used to break it -- a patch whose equivalent ellipses miss by
thousands of per cent (the columns ran together: '394.744403.64 %'), a patch
far from the origin (the spin-centre warning printed its bounding box as
'0.100000E+7'), an uncertain run (its warning gave the errors as
'0.781111E-2' below a line that says '7.8E-03') -- every line of standard
output and standard error must have:
  - no two numbers run together (a digit, a sign, a digit: '5.94-100.00');
  - no number in gfortran's G form ('0.100000E+7', '0.781111E-2') and every
    exponent with at least two digits, as the summary's own lines print them;
  - no field of asterisks (a number too wide for its format).

    test_summary_format.py PATH/TO/kcreep
"""
import re

import kctest as kc

GLUED = re.compile(r"\d[-+]\d")
G_FORM = re.compile(r"(?<![\d.])[-+]?0\.[1-9]\d*E[-+]?\d")
SHORT_EXPONENT = re.compile(r"\dE[-+]?\d(?!\d)")
STARS = re.compile(r"\*\*\*")

CASES = {
    # two 2-cell pieces 24 cells apart: the equivalent ellipses miss C23 by 4,400 and 8,000 %
    "far_pieces": "&patch shape = 'mask', mask_rows = '##......................##', dx = 1, dy = 1 /\n"
                  "&solver target_error = 0 /\n",
    # a patch a million lengths from the origin, the spin centre: the bounding-box warning
    "far_away": "&patch shape = 'mask', mask_rows = '####', '####', '####', '####', dx = 1, dy = 1, "
                "x0 = 1e6, y0 = -2e-4 /\n&solver target_error = 0 /\n",
    # an uncertain estimate: the warning lists the errors and the targets
    "uncertain": "&patch shape = 'mask', mask_rows = '..####..', '.######.', '########', '########', "
                 "'.######.', '..####..', dx = 1, dy = 1 /\n&solver target_error = 1e-5, cell_budget = 1000 /\n",
}

folder = kc.setup()
seen_warnings = 0
for name, text in CASES.items():
    rc, out, err, _ = kc.run(text, folder, name=name, expect_ok=False)
    kc.check(rc == 0, f"{name}: exit 0 ({err.strip()[:200]})")
    lines = [l for l in (out + err).splitlines() if l.strip() and not l.startswith("kcreep 0")]
    seen_warnings += sum("warning" in l.lower() for l in lines)
    for line in lines:
        for rule, pattern in (("numbers run together", GLUED), ("gfortran's G form", G_FORM),
                              ("a one-digit exponent", SHORT_EXPONENT), ("a field of asterisks", STARS)):
            hit = pattern.search(line)
            kc.check(hit is None, f"{name}: {rule} {hit.group(0) if hit else ''!r} in {line.strip()[:160]!r}")
kc.check(seen_warnings >= 4, f"the cases gave warnings to check ({seen_warnings} lines)")

# Issue 45, item 7: a contact table's summary (its rows' fields: the unit test
# unit_wheel_rail_summary gives them numbers too wide for fixed formats) and its
# time line, which must count the rolling stage: with 4 creepage points on one
# shift's patch the rolling stage takes most of the run (measured here, one thread:
# the line said wall 0.86 s, the table alone, beside rolling 1.27 s, before).
import os  # noqa: E402
import subprocess  # noqa: E402
import time  # noqa: E402
text = kc.s1002_case("&rolling mu = 0.3, creepages = 0 0 0, 1e-3 0 0, 2e-3 0 0, 0 2e-3 0 /\n")
if text is not None:
    text = text.replace("shift_to = 1", "shift_to = 0")   # one shift: the table 0.3 s, rolling 4 points
if text is None:
    kc.check(False, f"the profiles of input/s1002_uic60.nml are not at {kc.PROFILES}")
else:
    with open(os.path.join(folder, "s1002_roll.nml"), "w") as f:
        f.write(text)
    t0 = time.time()
    proc = subprocess.run([kc.KCREEP, "s1002_roll.nml"], cwd=folder, capture_output=True, text=True,
                          env=dict(os.environ, OMP_NUM_THREADS="1"))   # (the thread choice is item 2's)
    elapsed = time.time() - t0
    kc.check(proc.returncode == 0, f"S1002 with &rolling runs ({proc.stderr.strip()[-200:]})")
    for line in (proc.stdout + proc.stderr).splitlines():
        for rule, pattern in (("numbers run together", GLUED), ("a field of asterisks", STARS)):
            hit = pattern.search(line)
            kc.check(hit is None, f"s1002_roll: {rule} {hit.group(0) if hit else ''!r} in {line.strip()[:160]!r}")
    rolling = re.search(r"mu = *\S+, *([\d.]+) s(?: on \d+ thread\(s\))?;", proc.stdout)
    wall = re.search(r"time \[s\]: wall *([\d.]+)", proc.stdout)
    kc.check(rolling is not None and wall is not None, f"the rolling line and the time line: {proc.stdout[-400:]!r}")
    if rolling and wall:
        kc.check(float(wall.group(1)) >= float(rolling.group(1)) and float(wall.group(1)) >= 0.6 * elapsed,
                 f"the time line counts the rolling stage: wall {wall.group(1)} s >= rolling {rolling.group(1)} s "
                 f"and >= 0.6 x the run's {elapsed:.2f} s")
kc.finish()
