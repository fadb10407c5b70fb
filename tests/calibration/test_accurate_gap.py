"""The accurate mode on a gap: the Hertzian gaps whose contact ellipse has
a/b = 2 (square cells) and 0.5 (cells long in y), nu = 0.25, run at
&solver target_error = 1e-4 with kcreep's levels and estimate, against the
ellipse with Hertz's semi-axes from kcreep's ellipse path at 1e-4
(hertz_gaps.py; its stated error is the reference's u).

Checks: each run `ok`, each error within its estimate and within its target
(1e-4, C23 3e-4), allowing u. Measured (docs/accuracy.md, "Gaps: one contact
area, sampled by the ladder"): about 30 s and 0.8 GB on one core.

usage: test_accurate_gap.py KCREEP
"""
import os
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import kctest as kc  # noqa: E402
from hertz_gaps import KEYS, Runner, gap_run, hertz, rx_for_aspect  # noqa: E402

TARGET = 1e-4


def main():
    kc.setup()
    with tempfile.TemporaryDirectory() as work:
        runner = Runner(kc.KCREEP, work)
        for ratio in (2.0, 0.5):
            rx = rx_for_aspect(ratio)
            a, b = hertz(rx, 1.0, 0.01)
            ref = runner.run(f"&patch semi_a = {a!r}, semi_b = {b!r} /\n&material g = 1, nu = 0.25 /\n"
                             "&solver target_error = 1e-4 /\n")
            run = gap_run(runner, rx, 0.25, f"&solver target_error = {TARGET!r} /\n")
            case = f"Hertz a/b = {ratio:g} (rx = {rx:.6f})"
            kc.check(run["verdict"] == "ok", f"{case}: verdict {run['verdict']} in {run['wall']:.1f} s")
            for key in KEYS:
                err_key = "err" + key[1:]
                error = abs(run[key] / ref[key] - 1)
                u, estimate = ref[err_key], run[err_key]
                target = 3 * TARGET if key == "c23" else TARGET
                kc.check(error <= estimate + u and error <= target + u,
                         f"{case} {key.upper()}: error {100 * error:.4f} % within the estimate "
                         f"{100 * estimate:.4f} % and the target {100 * target:g} % (u {100 * u:.4f} %)")
    kc.finish()


if __name__ == "__main__":
    main()
