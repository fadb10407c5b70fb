"""Hertzian gaps for the calibration tests: Hertz's contact ellipse of the gap
h = x^2/(2 rx) + y^2/(2 ry) (elliptic integrals, scipy), and a runner of the
kcreep program that returns the first table row.

The gap runs are kcreep's own: the estimate each checks is the one the
program computes (kcreep_gap_levels, kcreep_refine_estimate). The reference
is that ellipse's coefficients from kcreep's ellipse path at target_error
1e-4 (the refined table or solved ellipse levels: no gap, no normal problem),
its stated error the reference's u. Needs scipy (/usr/bin/python3).
"""
import math
import os
import subprocess

from scipy.optimize import brentq
from scipy.special import ellipe, ellipk

KEYS = ("c11", "c22", "c23")


def hertz(rx, ry, delta):
    """Hertz's semi-axes (along x, along y) for h = x^2/(2 rx) + y^2/(2 ry) at approach delta."""
    a_, b_ = 1 / (2 * rx), 1 / (2 * ry)
    swap = a_ > b_
    if swap:
        a_, b_ = b_, a_
    if abs(b_ / a_ - 1) < 1e-12:
        a = b = math.sqrt(delta / (2 * a_))
    else:
        m = brentq(lambda m: (ellipe(m) / (1 - m) - ellipk(m)) / (ellipk(m) - ellipe(m)) - b_ / a_,
                   1e-12, 1 - 1e-14)
        k, e = ellipk(m), ellipe(m)
        a = math.sqrt(delta * (k - e) / (k * a_ * m))
        b = a * math.sqrt(1 - m)
    return (b, a) if swap else (a, b)


def rx_for_aspect(ratio, delta=0.01):
    """rx (ry = 1) whose Hertz ellipse has a/b = ratio; the bracket [0.01, 100]
    as the documented runs had it (the root's last digits, and with them the
    levels, depend on it), wider for a/b > 10."""
    def aspect_gap(rx):
        a, b = hertz(rx, 1.0, delta)
        return a / b - ratio
    return brentq(aspect_gap, 0.01, 100.0 if aspect_gap(100.0) > 0 else 1e4)


class Runner:
    """Runs kcreep on namelists in a work folder (one thread)."""

    def __init__(self, kcreep, work):
        self.kcreep, self.work, self.count = kcreep, work, 0

    def run(self, text, files=None):
        """Run a namelist; the table's first row as a dict, and the wall time."""
        self.count += 1
        name = f"case{self.count}"
        for fname, content in (files or {}).items():
            with open(os.path.join(self.work, fname), "w") as f:
                f.write(content)
        path = os.path.join(self.work, name + ".nml")
        with open(path, "w") as f:
            f.write(text)
        proc = subprocess.run(["/usr/bin/time", "-f", "%e", self.kcreep, path], cwd=self.work,
                              capture_output=True, text=True, env=dict(os.environ, OMP_NUM_THREADS="1"))
        if proc.returncode != 0:
            raise RuntimeError(f"kcreep failed on\n{text}\n{proc.stderr}")
        wall = float(proc.stderr.strip().split("\n")[-1])
        with open(os.path.join(self.work, name + ".tab")) as f:
            lines = f.read().splitlines()
        head = next(line for line in lines if line.startswith("# case")).split()[1:]
        row = next(line for line in lines if not line.startswith("#")).split()
        out = {}
        for k, v in zip(head, row):
            try:
                out[k] = float(v)
            except ValueError:
                out[k] = v
        out["wall"] = wall
        return out


def reference(runner, a, b, nu):
    """The ellipse a x b at Poisson's ratio nu by kcreep's ellipse path at target 1e-4."""
    return runner.run(f"&patch shape = 'ellipse', semi_a = {a!r}, semi_b = {b!r} /\n"
                      f"&material g = 1, nu = {nu} /\n&solver target_error = 1e-4 /\n")


def gap_run(runner, rx, nu, solver=""):
    """The Hertzian gap rx, ry = 1, approach 0.01 as a user runs it (&normal and nothing else)."""
    return runner.run(f"&patch shape = 'gap' /\n&normal rx = {rx!r}, ry = 1.0, approach = 0.01 /\n"
                      f"&material g = 1, nu = {nu} /\n" + solver)
