"""Error control (&solver target_error): the estimate err11 err22 err23 bounds
the error measured against a fine-grid extrapolation on cheap cases, and the
verdict says 'uncertain' exactly when an estimate misses its target.

References: a rectangle mask is refined exactly (every cell split), so its
fine-grid reference is a least-squares fit c0 + K h + L h^1.5 through splits of
4 to 12 (96 x 48 cells), computed here; for the unit circle the reference is the
refined table docs/data/kalker_refined.dat (levels 32 to 96 cells across,
with its own uncertainty u, which the check allows for)."""
import math
import os
import kctest as kc

folder = kc.setup()
repo = kc.REPO
COEFFS = ("c11", "c22", "c23")


def nml(patch, material="nu=0.25", solver=""):
    # written directly (not kctest.namelist): these runs test kcreep's own defaults
    return f"&patch {patch} /\n&material {material} /\n&solver {solver} /\n"


def rect_mask(mx, my, lx=2.0, ly=1.0):
    dx, dy = lx / mx, ly / my
    rows = ", ".join("'" + "#" * mx + "'" for _ in range(my))
    return (f"shape='mask', mask_rows={rows}, dx={dx!r}, dy={dy!r}, "
            f"x0={-lx / 2 + dx / 2!r}, y0={-ly / 2 + dy / 2!r}")


def fit_limit(hs, fs):
    """f0 of the least-squares fit f0 + K h + L h^1.5 (a rectangle's splits 1 to 12
    fit it to 4e-5 from any four of them, while a straight line drifts by 0.2 %)."""
    rows = [[1.0, h, h ** 1.5] for h in hs]
    ata = [[sum(r[a] * r[b] for r in rows) for b in range(3)] for a in range(3)]
    atf = [sum(r[a] * f for r, f in zip(rows, fs)) for a in range(3)]
    for c in range(3):                      # Gauss-Jordan on the 3 x 3 normal equations
        p = ata[c][c]
        for r in range(3):
            if r != c:
                q = ata[r][c] / p
                ata[r] = [x - q * y for x, y in zip(ata[r], ata[c])]
                atf[r] -= q * atf[c]
    return atf[0] / ata[0][0]


# --- 1. mask: the default run (splits 1..4 of an 8 x 4 rectangle) against splits 4..12
_, out, err, t = kc.run(nml(rect_mask(8, 4)), folder, "rect")
row = t[0]
fine = {}
for s in (4, 6, 8, 12):
    fine[s] = kc.run(nml(rect_mask(8 * s, 4 * s), solver="target_error=0"), folder, f"rect{s}")[3][0]
for c, e in zip(COEFFS, ("err11", "err22", "err23")):
    ref = fit_limit([1 / s for s in fine], [fine[s][c] for s in fine])
    true = abs(row[c] - ref) / abs(ref)
    kc.check(math.isfinite(row[e]) and row[e] >= true,
             f"rectangle mask: {e} = {row[e]:.2e} bounds the error {true:.2e} against splits 4-12 ({row[c]:.6f} vs {ref:.6f})")
kc.check(row["mx"] == 32 and row["my"] == 16, f"rectangle mask: finest split 4 x 4 ({row['mx']} x {row['my']})")

# --- 2. the unit circle on explicit grids (target_error = 0): the one-grid estimate
ref_rows = [r for r in kc.read_table(os.path.join(repo, "docs", "data", "kalker_refined.dat"))
            if abs(r["a_over_b"] - 1) < 1e-9 and abs(r["nu"] - 0.25) < 1e-9]
kc.check(len(ref_rows) == 1, "refined table has the unit circle at nu = 0.25")
if ref_rows:
    ref = ref_rows[0]
    for m in (24, 32, 40):
        r = kc.run(nml(f"semi_a=1, semi_b=1, mx={m}, my={m}", solver="target_error=0"), folder, f"c{m}")[3][0]
        for c, e, u in zip(COEFFS, ("err11", "err22", "err23"), ("u11", "u22", "u23")):
            true = abs(r[c] - ref[c]) / ref[c]
            kc.check(r[e] + ref[u] / ref[c] >= true,
                     f"circle {m} x {m}: {e} = {r[e]:.2e} bounds the error {true:.2e} (reference u {ref[u] / ref[c]:.1e})")
        kc.check(r["verdict"] == "ok", f"circle {m} x {m}, target_error = 0: never uncertain ({r['verdict']})")

# --- 3. 'uncertain' when it should
code, out, err, t = kc.run(nml("semi_a=1, semi_b=1, mx=24, my=24", solver="target_error=1e-4"), folder, "strict")
kc.check("uncertain" in t[0]["verdict"] and "uncertain:" in err,
         f"24 x 24 grid, target 1e-4: verdict {t[0]['verdict']} and a warning")
# ... that says what to change (issue 45: the README's 60 x 40 ended uncertain with no hint)
kc.check("leave mx, my out and kcreep chooses grids that meet the target" in err
         and "target_error = 0 takes this grid with its estimate" in err,
         f"24 x 24 grid, target 1e-4: the warning names the fix ({err.strip()!r})")
code, out, err, t = kc.run(nml("semi_a=1, semi_b=1, mx=24, my=24", solver="target_error=0.05"), folder, "loose")
kc.check(t[0]["verdict"] == "ok" and max(t[0]["err11"], t[0]["err22"]) <= 0.05 and t[0]["err23"] <= 0.15,
         f"24 x 24 grid, target 5 %: ok ({t[0]['verdict']}, estimates {t[0]['err11']:.1e} {t[0]['err22']:.1e})")
code, out, err, t = kc.run(nml("semi_a=1, semi_b=1, mx=10, my=10"), folder, "tiny")
kc.check(all(math.isnan(t[0][e]) for e in ("err11", "err22", "err23")) and "too coarse" in err
         and "uncertain" in t[0]["verdict"], f"10 x 10 grid: no estimate, said, uncertain ({t[0]['verdict']})")
# the warnings say what to change and give a missing estimate in words (issue 45: 'NaN, NaN, NaN')
kc.check("give mx, my of at least 24" in err and "C23 not estimated, not estimated, not estimated against" in err
         and "NaN" not in err, f"10 x 10 grid: the warnings name the fix, no NaN ({err.strip()!r})")
# target_error = 0 sets no target, but ok needs a finite estimate (issue 45: ok without one)
code, out, err, t = kc.run(nml("semi_a=1, semi_b=1, mx=10, my=10", solver="target_error=0"), folder, "tiny0")
kc.check(t[0]["verdict"] == "uncertain" and "uncertain: no error estimate of C11, C22, C23" in err,
         f"10 x 10 grid, target_error = 0: no estimate, uncertain ({t[0]['verdict']})")

# --- 4. the solved run on an ellipse (kcreep chooses the levels) against the refined table
# (method = 'iterative': the default 'auto' answers such an ellipse from the table itself).
# Measured (lab/accuracy_table.sh --solver "method = 'iterative'"): a/b = 0.2, nu = 0.25
# ends ok with estimates of 0.03-0.09 % against errors below 0.02 % (reference u 0.02-0.05 %)
ref_rows = [r for r in kc.read_table(os.path.join(repo, "docs", "data", "kalker_refined.dat"))
            if abs(r["a_over_b"] - 0.2) < 1e-9 and abs(r["nu"] - 0.25) < 1e-9]
if ref_rows:
    ref = ref_rows[0]
    patch = f"semi_a={math.sqrt(0.2)!r}, semi_b={1 / math.sqrt(0.2)!r}"
    r = kc.run(nml(patch, solver="method='iterative'"), folder, "e02")[3][0]
    kc.check(r["verdict"] == "ok" and r["mx"] >= 56, f"a/b = 0.2 solved run: ok ({r['verdict']}, {r['mx']} x {r['my']})")
    kc.check(abs(r["my"] / r["mx"] - 5) < 0.1, f"a/b = 0.2 at the default target: near-square cells ({r['mx']} x {r['my']})")
    for c, e, u in zip(COEFFS, ("err11", "err22", "err23"), ("u11", "u22", "u23")):
        true = abs(r[c] - ref[c]) / ref[c]
        kc.check(r[e] + ref[u] / ref[c] >= true,
                 f"a/b = 0.2 solved run: {e} = {r[e]:.2e} bounds the error {true:.2e} (reference u {ref[u] / ref[c]:.1e})")
    # the default run: the table, whose stated uncertainty is within the target here
    r = kc.run(nml(patch), folder, "e02_auto")[3][0]
    kc.check(r["verdict"] == "ok" and r["n"] == 0 and abs(r["c11"] / ref["c11"] - 1) < 1e-5,
             f"a/b = 0.2 default run: the refined table, ok ({r['verdict']}, {r['n']} cells, c11 {r['c11']})")
    # ... and a target tighter than the table's uncertainty is solved
    r = kc.run(nml(patch, solver="target_error=1e-4"), folder, "e02_tight")[3][0]
    kc.check(r["n"] > 0, f"a/b = 0.2, target 1e-4: solved, not the table ({r['n']} cells)")
    # tighter than the default: N x N cells over the bounding box, long in y
    # (kcreep_refine_estimate.ellipse_cells_long_in_y); measured: ok at 452 x 452 in about 3.5 s,
    # errors against independent references of 0.001-0.007 % (docs/accuracy.md, "Ellipses")
    kc.check(r["mx"] == r["my"] and r["verdict"] == "ok",
             f"a/b = 0.2, target 1e-4: cells long in y, ok ({r['mx']} x {r['my']}, {r['verdict']})")
    for c, e, u in zip(COEFFS, ("err11", "err22", "err23"), ("u11", "u22", "u23")):
        true = abs(r[c] - ref[c]) / ref[c]
        kc.check(r[e] + ref[u] / ref[c] >= true,
                 f"a/b = 0.2, target 1e-4: {e} = {r[e]:.2e} bounds the error {true:.2e} (reference u {ref[u] / ref[c]:.1e})")
# a loose target stops at the base levels: finest 96 cells across (kcreep_error_run base_levels)
r = kc.run(nml("semi_a=1, semi_b=1", solver="target_error=0.01, method='iterative'"), folder, "loose_e")[3][0]
kc.check(r["verdict"] == "ok" and r["mx"] == 96, f"circle, target 1 %: ok on the base levels ({r['mx']} x {r['my']})")

# the levels' GMRES stops at min(0.1 x target, 1e-4) when no tolerance is given
# (kcreep_refine_estimate level_solver_tolerance; 1e-4 at this target): fewer iterations
# (circle at 1e-2: measured 8 against 26 on its finest level), the same coefficients
# to a small part of the target (measured at target 1e-2 on levels with a blended
# edge: C11, C22, C23 moved by 1.6e-5, 1.5e-5, 3.7e-5; allowed 2e-2 x target = 2e-4,
# twice the levels' residual), and no 'inaccurate' flag
given = kc.run(nml("semi_a=1, semi_b=1", solver="target_error=0.01, method='iterative', tolerance=1e-11"),
               folder, "loose_given")[3][0]
kc.check(r["iterations"] < given["iterations"] and r["verdict"] == "ok",
         f"levels without a tolerance: {r['iterations']} GMRES iterations on the finest level against "
         f"{given['iterations']} with tolerance 1e-11, verdict {r['verdict']}")
for c in COEFFS:
    kc.check(abs(r[c] / given[c] - 1) <= 2e-2 * 0.01, f"{c}: {r[c]:.8f} against {given[c]:.8f} at tolerance 1e-11")

# --- 5. bad input
code, out, err, t = kc.run(nml("semi_a=1, semi_b=1", solver="target_error=-1"), folder, "bad", expect_ok=False)
kc.check(code == 2 and "target_error" in err and "allowed" in err, f"target_error = -1: exit 2, named ({err.strip()})")
code, out, err, t = kc.run(nml("semi_a=5, semi_b=1, mx=40, my=40", solver="scheme='collocation'"), folder, "col",
                           expect_ok=False)
kc.check(code == 2 and "col.nml" in err and "cells long in x" in err and t is None,
         f"collocation on dx/dy = 5 with a target: refused, naming the input ({err.strip()[:120]})")
code, out, err, t = kc.run(nml("semi_a=5, semi_b=1, mx=40, my=40", solver="scheme='collocation', target_error=0"),
                           folder, "col0")
kc.check(code == 0 and "degenerate" in t[0]["verdict"], f"the same grid as given (target 0): run and flagged ({t[0]['verdict']})")
code, out, err, t = kc.run(nml("semi_a=5, semi_b=1", solver="scheme='collocation', target_error=0.01"), folder, "colsq")
kc.check(code == 0 and abs(t[0]["mx"] / t[0]["my"] - 5) < 0.1,
         f"collocation under error control: kcreep's own near-square grid ({t[0]['mx']} x {t[0]['my']})")
# --- 6. the split ladder ends (scripts/fuzz.py findings): without phi, C23 has
# no estimate and is not waited for; a mask that does not converge stops at
# max_split = 32 instead of splitting one level at a time up to the budget
code, out, err, t = kc.run(nml("shape='mask', mask_rows='.##.', '####', '.##.', dx=0.1, dy=0.1, x0=-0.15, y0=-0.1",
                               solver="load_cases='xi eta'"), folder, "nophi")
kc.check(code == 0 and t[0]["mx"] <= 4 * 8 and t[0]["err11"] <= 1e-3 and t[0]["err22"] <= 1e-3,
         f"load cases xi eta: the ladder stops where C11, C22 meet the target (finest {t[0]['mx']} x {t[0]['my']}, "
         f"was 141 x 141 splits)")
# ... and the run is `ok` (C23 was not asked for), its summary shows C11 and
# C22's estimates with '-' for C23's and the equivalent ellipses' C11, C22
# errors (before: verdict uncertain, "none (see the warnings)", NaN %)
summary = [line for line in out.splitlines() if "estimated relative error" in line or "equivalent ellipse (box)" in line]
kc.check(t[0]["verdict"] == "ok" and len(summary) == 2 and summary[0].split(":")[1].split()[2] == "-"
         and "NaN" not in summary[1].split("(")[-1].split()[0:2],
         f"load cases xi eta: verdict {t[0]['verdict']}; {' | '.join(s.strip() for s in summary)}")
code, out, err, t = kc.run(nml("shape='mask', mask_rows='#.#', '.#.', '#.#', dx=1, dy=1, x0=-1, y0=-99999999999"),
                           folder, "far")
kc.check(code == 0 and t[0]["mx"] == 3 * 32 and "finest split kcreep tries" in err and t[0]["verdict"] != "ok",
         f"five cells 1e11 from the spin centre: stopped at 32 x 32 splits, uncertain and saying why "
         f"({t[0]['mx']} x {t[0]['my']}, {t[0]['verdict']})")

# --- 7. a budget too small for the base levels scales them below 56 cells
# across, where the estimate was not calibrated (levels bend with L h^2; on
# the S1002 flange strips such estimates moved by up to 10 times): the run
# ends uncertain with the warning that says why, whatever its estimates
code, _, err, t = kc.run(nml("semi_a=2, semi_b=1", solver="method='iterative', cell_budget=5000"), folder, "scaled")
kc.check(code == 0 and t[0]["verdict"] == "uncertain" and "scaled the levels down to" in err,
         f"cell_budget = 5000 on a/b = 2: levels scaled below 56 across, uncertain ({t[0]['verdict'] if t else None})")
code, _, err, t = kc.run(nml("semi_a=2, semi_b=1", solver="method='iterative'"), folder, "unscaled")
kc.check(code == 0 and "scaled the levels" not in err, "the default budget on a/b = 2: base levels as calibrated, no such warning")
kc.finish()
