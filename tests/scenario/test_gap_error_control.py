"""Error control of a patch found by the normal problem (&patch shape = 'gap').

Hertzian gap h = (x^2 + y^2) / 2 (R = 1), approach 0.01 (contact radius 0.1),
G = 1, nu = 0.25. Reference: the same gap solved as given on explicit grids of
64 to 128 cells across the contact diameter, the first-order fit through them
(as kcreep's levels are fitted) with its 95 % interval u.
1. Levels of finer geometry (target 0.01: the base levels, 24 to 56 cells
   across): the estimate bounds the error against the reference (allowing u),
   the verdict is ok, the contact area is Hertz's to the measured accuracy.
2. A strict target (1e-4) that a small cell budget (20,000 cells) cannot
   meet: 'uncertain', with a warning giving the estimates. (Within the
   default budget this sphere now meets 1e-4.)
3. target_error = 0: the automatic grid as given (fewer cells than the levels'
   finest), the estimate from the geometry on cells twice the size bounds the
   error, never 'uncertain'; a grid too coarse for that estimate gets NaN and
   a warning saying so.
usage: test_gap_error_control.py KCREEP
"""
import math
import os
import sys

import kctest as kc

sys.path.insert(0, os.path.join(kc.REPO, "tools", "maintenance"))
from kcreep_levels import student_t95  # noqa: E402  (the library's table, read from its source)

folder = kc.setup()
GAP = "&patch shape = 'gap'{grid} /\n&normal rx = 1, ry = 1, approach = 0.01{more} /\n&material g = 1, nu = 0.25 /\n"
KEYS = ("c11", "c22", "c23")


def fit(h, f):
    """f0 + K h by least squares: f0 and its 95 % interval."""
    m = len(h)
    hm, fm = sum(h) / m, sum(f) / m
    shh = sum((x - hm) ** 2 for x in h)
    k = sum((x - hm) * (y - fm) for x, y in zip(h, f)) / shh
    f0 = fm - k * hm
    s2 = sum((y - f0 - k * x) ** 2 for x, y in zip(h, f)) / (m - 2)
    return f0, student_t95(m - 2) * math.sqrt(s2 * (1 / m + hm ** 2 / shh))


# the reference: explicit grids centred on the contact, N cells across its diameter 0.2
hs, cs = [], {k: [] for k in KEYS}
for n in (64, 80, 96, 112, 128):
    d = 0.2 / n
    m = int(1.3 * n) | 1
    x0 = -(m - 1) * d / 2
    r = kc.coefficients(GAP.format(grid=f", mx = {m}, my = {m}, dx = {d!r}, dy = {d!r}, x0 = {x0!r}, y0 = {x0!r}",
                                   more="") + "&solver target_error = 0 /\n", folder, f"ref{n}")
    hs.append(1 / n)
    for k in KEYS:
        cs[k].append(r[k])
ref = {k: fit(hs, cs[k]) for k in KEYS}
print("reference (fit through 64-128 across): " + ", ".join(f"{k} {v[0]:.5f} +- {v[1]:.5f}" for k, v in ref.items()))


# measured (2 cores, loaded): errors of the base levels 24-56 against this reference
# 0.11 / 0.01 / 0.21 % for C11 / C22 / C23, estimates 0.24 / 0.14 / 0.18 %, u 0.08 /
# 0.06 / 0.06 %; the whole test 12 s
def bounded(row, label):
    for k in KEYS:
        value, (r0, u) = row[k], ref[k]
        error, estimate = abs(value / r0 - 1), row["err" + k[1:]]
        kc.check(error <= estimate + u / abs(r0),
                 f"{label}: {k} error {error:.2e} within the estimate {estimate:.2e} (+ the reference's u "
                 f"{u / abs(r0):.1e})")


# 1. levels of finer geometry
code, out, err, tab = kc.run(GAP.format(grid="", more="") + "&solver target_error = 0.01 /\n", folder, "levels")
row = tab[0]
bounded(row, "levels 24-56")
kc.check(row["verdict"] == "ok", f"levels 24-56, target 0.01: verdict {row['verdict']}")
# the fitted contact area against pi a^2 (Hertz): measured -0.2 % here, at most 0.5 % over
# the Hertzian calibration gaps (docs/accuracy.md); the staircase of one grid is 1-6 % off
kc.check(abs((row["c"] / 0.1) ** 2 - 1) < 0.02, f"fitted contact area vs Hertz ({(row['c'] / 0.1) ** 2 - 1:+.2e})")

# 2. a strict target
code, out, err, tab = kc.run(GAP.format(grid="", more="") + "&solver target_error = 1e-4, cell_budget = 20000 /\n",
                             folder, "strict")
row = tab[0]
kc.check(row["verdict"] == "uncertain" and "uncertain: estimated relative errors" in err,
         f"target 1e-4: verdict {row['verdict']} and a warning")
kc.check(all(0 < row["err" + k[1:]] < 0.01 for k in KEYS), "target 1e-4: estimates finite (" +
         ", ".join(f"{row['err' + k[1:]]:.1e}" for k in KEYS) + ")")
bounded(row, "levels within 20,000 cells")

# 3. the grid as given
code, out, err, tab = kc.run(GAP.format(grid="", more="") + "&solver target_error = 0 /\n", folder, "single")
row = tab[0]
bounded(row, "one grid (cells_across 60)")
kc.check(row["verdict"] == "ok" and "uncertain" not in err, "target 0: never 'uncertain'")
kc.check(row["n"] < 2000, f"target 0: the automatic grid as given ({int(row['n'])} contact cells)")
code, out, err, tab = kc.run(GAP.format(grid="", more=", cells_across = 24") + "&solver target_error = 0 /\n",
                             folder, "coarse")
row = tab[0]
kc.check(all(kc.isnan(row["err" + k[1:]]) for k in KEYS) and "too coarse to judge itself" in err,
         "cells_across 24: no estimate (NaN) and a warning says why")
# no ok without an estimate, target 0 too (issue 45), and the warning names what to set
kc.check(row["verdict"] == "uncertain" and "raise &normal cells_across" in err,
         f"cells_across 24: uncertain, the warning names cells_across ({row['verdict']})")
kc.finish()
