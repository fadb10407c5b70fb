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
kc.finish()
