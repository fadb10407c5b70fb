"""The estimate of a solved ellipse (kcreep_refine_estimate shape_level_estimate
on kcreep's ellipse levels: base_levels, next_level_growth, ellipse_fit_min,
ellipse_fit_width, order_margin, the cell budget) against the refined table,
an independent discretisation (staircase levels to 1024 cells across,
docs/accuracy.md, "The refined table of ellipses"; its stated uncertainty u).

Ellipses a/b = 0.1, 0.2, 0.5, 1, 2, 3.33, 5, 10 (c = 1) at nu = 0.25, solved
as a user asks (&solver method = 'iterative', the default target 1e-3:
kcreep chooses the levels); the reference is the same ellipse with
method = 'table'.

Checks: every run `ok`; every error within its estimate allowing u (24 of
24 measured); the median estimate / error within [3, 10]: measured 6.8 here
(7.1 over nu = 0, 0.25 and 0.5, docs/accuracy.md, "Ellipses"); half the
estimate leaves a/b = 2's C11 unbounded (error 0.0097 % against an estimate
of 0.016 %) and the median at 3.4, twice the estimate puts it at 13.6.
About 15 s on one core.

usage: test_ellipse_levels.py KCREEP
"""
import os
import statistics
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import kctest as kc  # noqa: E402

RATIOS = (0.1, 0.2, 0.5, 1, 2, 3.33, 5, 10)
MEDIAN_RANGE = (3.0, 10.0)


def main():
    folder = kc.setup()
    ratios = []
    for ratio in RATIOS:
        patch = f"&patch semi_a = {ratio ** 0.5!r}, semi_b = {ratio ** -0.5!r} /\n&material nu = 0.25 /\n"
        rows = {}
        for method in ("iterative", "table"):
            rows[method] = kc.run(patch + f"&solver method = '{method}' /\n", folder, f"{method}_{ratio:g}")[3][0]
        solved, ref = rows["iterative"], rows["table"]
        case = f"a/b = {ratio:g}"
        kc.check(solved["verdict"] == "ok" and ref["verdict"] == "ok",
                 f"{case}: verdicts {solved['verdict']} (solved), {ref['verdict']} (table)")
        for c in ("11", "22", "23"):
            error = abs(solved["c" + c] / ref["c" + c] - 1)
            estimate, u = solved["err" + c], ref["err" + c]
            kc.check(error <= estimate + u, f"{case} C{c}: error {100 * error:.4f} % within the estimate "
                                             f"{100 * estimate:.4f} % (u {100 * u:.4f} %)")
            ratios.append(estimate / max(error, 1e-12))
    median = statistics.median(ratios)
    kc.check(MEDIAN_RANGE[0] <= median <= MEDIAN_RANGE[1],
             f"{len(ratios)} cases, median estimate / error {median:.2f} within {MEDIAN_RANGE}")
    kc.finish()


if __name__ == "__main__":
    main()
