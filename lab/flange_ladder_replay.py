#!/usr/bin/python3
"""The S1002 / UIC60 table's contact-area ladders replayed (issue 46, speed;
lab/notes/wheel_rail_speed.md, "The ladders replayed").

lab/data/s1002_ladder_levels.dat holds every row of
scripts/figures/s1002_uic60_contact.nml (161 shifts, main at 4f01048) with
its ladder forced through the levels 56, 64, ..., 196, 224 cells across,
each level's f11, f22, f23 and CPU time, and the row's normal-grid estimate.
It was made with two temporary changes to src/pipeline/kcreep_level_ladder.f90
(not committed): the region's base levels replaced by that list (the loop
then fits once, after the last level), and a print of each level's
patch%mx, patch%my, patch%n, f(1,1), f(2,2), f(2,3) and cpu_time, of
other_error at the fit, and (kcreep_wheel_rail_run) of the shift; 192 s
user on one thread.

This script replays kcreep's stopping rule (run_shape_levels: the fit
f0 + K h through the finest ellipse_fit_width = 8 levels, the estimate t95 x
se(f0) + 0.1 |f0 - f(finest)|, combined in quadrature with the normal
grid's; levels_done from the second fit on; the region's cap of 172 cells
across) on other level sequences, costed by the logged CPU times, and
compares the base levels' fit (56-96) with the fit through 96-224:

  /usr/bin/python3 lab/flange_ladder_replay.py

A level reached by another sequence is taken as logged (its GMRES start,
the previous level's traction, differs: within the solver's residual).
"""
import os
import sys

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DATA = os.path.join(ROOT, "lab", "data", "s1002_ladder_levels.dat")
T95 = {1: 12.706, 2: 4.303, 3: 3.182, 4: 2.776, 5: 2.571, 6: 2.447, 7: 2.365, 8: 2.306, 9: 2.262, 10: 2.228}
TARGETS = np.array([1e-3, 1e-3, 3e-3])      # C11, C22, C23 at the default target_error
FIT_MIN, FIT_WIDTH, ORDER_MARGIN = 5, 8, 0.1  # kcreep_refine_constants
LADDER = [56, 64, 72, 84, 96, 112, 128, 148, 172]


def read_rows(path):
    """{shift: (other_error(3), {level: (f(3), cpu)})} in file order."""
    rows = {}
    for line in open(path):
        if line.startswith("#"):
            continue
        w = line.split()
        shift = float(w[0])
        other = np.array([float(x) for x in w[1:4]])
        level = int(w[4])
        f = np.array([float(x) for x in w[8:11]])
        rows.setdefault(shift, (other, {}))[1][level] = (f, float(w[11]))
    return rows


def fit(levels, values):
    """kcreep's shape_level_estimate: limit and relative estimate."""
    h = 1.0 / np.asarray(levels, float)
    a = np.vstack([np.ones_like(h), h]).T
    c, *_ = np.linalg.lstsq(a, values, rcond=None)
    r = values - a @ c
    s2 = (r @ r) / (len(h) - 2)
    se = np.sqrt(np.linalg.inv(a.T @ a)[0, 0] * s2)
    f0 = c[0]
    return f0, (T95[len(h) - 2] * se + ORDER_MARGIN * abs(f0 - values[np.argmin(h)])) / abs(f0)


def replay(other, levels, ladder):
    """The ladder's run on the logged levels: (finest level, CPU s, 'ok' / 'done' / 'cap')."""
    used, cost = [], 0.0
    for level in ladder:
        used.append(level)
        cost += levels[level][1]
        if len(used) < FIT_MIN:
            continue
        window = used[-FIT_WIDTH:]
        own = np.array([fit(window, np.array([levels[x][0][j] for x in window]))[1] for j in range(3)])
        combined = np.sqrt(own**2 + other**2)
        if np.all(combined <= TARGETS):
            return level, cost, "ok"
        if len(used) > FIT_MIN and np.all(np.where(other > TARGETS, own, combined) <= TARGETS):
            return level, cost, "done"
    return used[-1], cost, "cap"


def main():
    rows = read_rows(DATA)
    print(f"{len(rows)} rows from {os.path.relpath(DATA, ROOT)}")
    print("\nLevel sequences replayed (CPU s of the levels, rows ending within the target):")
    sequences = {
        "kcreep's ladder (to 172)": LADDER,
        "the ladder to 196": LADDER + [196],
        "96 -> 128 -> 172": [56, 64, 72, 84, 96, 128, 172],
        "96 -> 128 -> 172 -> 224": [56, 64, 72, 84, 96, 128, 172, 224],
        "96 -> 148 -> 224": [56, 64, 72, 84, 96, 148, 224],
        "96 -> 112 -> 148 -> 196": [56, 64, 72, 84, 96, 112, 148, 196],
        "the base levels only": LADDER[:5],
    }
    for name, seq in sequences.items():
        total, ok = 0.0, 0
        for other, levels in rows.values():
            _, cost, verdict = replay(other, levels, seq)
            total += cost
            ok += verdict == "ok"
        print(f"  {name:28s} {total:6.1f} s  {ok:3d} ok")
    print("\nThe base levels' fit (56-96) against the fit through 96-224 (8 levels), rows +4.7 to +10 mm:")
    for j, name in enumerate(["C11", "C22", "C23"]):
        est, err, ref_est = [], [], []
        for shift, (other, levels) in rows.items():
            if shift < 4.65:
                continue
            b0, b_est = fit(LADDER[:5], np.array([levels[x][0][j] for x in LADDER[:5]]))
            ref = [96, 112, 128, 148, 172, 196, 224]
            r0, r_est = fit(ref, np.array([levels[x][0][j] for x in ref]))
            est.append(b_est)
            err.append(abs(b0 - r0) / abs(r0))
            ref_est.append(r_est)
        est, err, ref_est = map(np.array, (est, err, ref_est))
        q = est / err
        print(f"  {name}: median estimate {np.median(est):.2e}, |base - reference| {np.median(err):.2e}, "
              f"reference's own estimate {np.median(ref_est):.2e}; estimate / difference 10/25/50 % "
              f"{np.percentile(q, 10):.2f} / {np.percentile(q, 25):.2f} / {np.median(q):.2f}; "
              f"difference above the estimate {int((err > est).sum())} of {len(est)}, "
              f"above estimate + reference's {int((err > est + ref_est).sum())}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
