#!/usr/bin/env python3
"""The least-squares fit through an ellipse's levels and kcreep's estimate
from it, shared by the level studies (level_noise_study.py,
level_design_study.py, staircase_defect_study.py). Needs numpy
(/usr/bin/python3 with Debian's python3-numpy).

Levels: {N: {coefficient: value referred to the ellipse, "harmonic4": ...}}
as kcreep_levels.refer_to_ellipse gives them, N cells across the shorter axis.
"""
import math
import os
import sys

if __name__ == "__main__" and any(a in ("-h", "--help") for a in sys.argv[1:]):
    print("usage: lab/level_fit.py is imported by the level studies, not run\n" + __doc__)
    sys.exit(0)
import numpy as np  # noqa: E402

sys.path[:0] = [os.path.join(os.path.dirname(os.path.abspath(__file__)), d) for d in (".", "../tools/maintenance", "../scripts/convergence", "../tests/calibration")]
from kcreep_levels import student_t95  # noqa: E402


def fit_levels(levels, ns, coeff, quadratic=False, weighted=False, extra=()):
    """Fit f0 + K h [+ L h^2] + B harmonic4 [+ one coefficient per extra column]
    through the levels ns (h = 1/N; weighted: each level weighted by N).
    extra: functions of a level giving further columns. Returns (coefficients
    in that order, standard error of f0, degrees of freedom, each level's
    residual); the standard error is NaN without degrees of freedom left or
    with dependent columns."""
    h = np.array([1.0 / n for n in ns])
    columns = [np.ones_like(h), h] + ([h * h] if quadratic else []) + [np.array([levels[n]["harmonic4"] for n in ns])]
    columns += [np.array([column(levels[n]) for n in ns]) for column in extra]
    weight = 1.0 / h if weighted else np.ones_like(h)
    a = np.array(columns).T * weight[:, None]
    f = np.array([levels[n][coeff] for n in ns]) * weight
    coef = np.linalg.lstsq(a, f, rcond=None)[0]
    dof = len(ns) - a.shape[1]
    residual = f - a @ coef
    if dof <= 0 or np.linalg.matrix_rank(a) < a.shape[1]:
        return coef, float("nan"), dof, residual / weight
    return coef, math.sqrt(residual @ residual / dof * np.linalg.inv(a.T @ a)[0, 0]), dof, residual / weight


def kcreep_estimate(levels, ns, coeff, extra=()):
    """kcreep's estimate (kcreep_refine_estimate.ellipse_level_estimate): the
    straight line through the last 8 of the levels ns, t95 x SE
    plus 0.1 |f0 - f(finest)|, the finest level's extra columns taken off it.
    Returns (f0, relative estimate)."""
    window = ns[-8:]
    coef, se, dof, _ = fit_levels(levels, window, coeff, extra=extra)
    finest = levels[max(window)]
    f_finest = finest[coeff] - sum(c * column(finest) for c, column in zip(coef[3:], extra))
    return coef[0], (student_t95(dof) * se + 0.1 * abs(coef[0] - f_finest)) / abs(coef[0])
