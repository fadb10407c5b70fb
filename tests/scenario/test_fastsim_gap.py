"""FASTSIM on a patch found by the normal problem: the pressure comes from
the normal solve (pressure = 'normal', the default for shape = 'gap'), so
the creep table's fn is the normal problem's Fn and the curve saturates at
mu Fn; 'normal' is refused for a patch without a normal solve.

usage: test_fastsim_gap.py KCREEP SOURCE_DIR
"""
import os
import sys

import kctest as kc

folder = kc.setup()
source = os.path.abspath(sys.argv[2])
gap = os.path.join(source, "input", "wheel_rail.gap")
text = (f"&patch shape = 'gap' /\n"
        f"&normal gap_file = '{gap}', normal_force = 80000.0, e1 = 210000.0, nu1 = 0.28, e2 = 210000.0, nu2 = 0.28 /\n"
        "&solver scheme = 'backward' /\n"
        "&fastsim mu = 0.3, sweep_direction = 1 0 0, sweep_from = 1e-6, sweep_to = 3e-2, sweep_points = 12, "
        "sweep_spacing = 'log' /\n")
code, out, err, table = kc.run(text, folder, "wheel")
kc.check(code == 0, "gap + fastsim runs" + ("" if code == 0 else ": " + err))
creep = kc.read_table(os.path.join(folder, "wheel.creep"))
row = table[0]
kc.check("normal" in out and "pressure normal" in out, "the summary names the normal problem as pressure source")
kc.close(creep[0]["fn"], row["fn"], 1e-12, "creep table fn = the normal problem's Fn")
kc.close(row["fn"], 80000.0, 1e-8, "Fn as prescribed")
# the gap's contact area is under error control (levels of finer geometry): an estimate
kc.check(all(row[k] > 0 and not kc.isnan(row[k]) for k in ("err11", "err22", "err23")),
         "error estimates of the gap patch")
# small creepage: the slope is f11 (L1 = I1 / f11 makes FASTSIM's full-adhesion slope f11;
# measured 6e-16 at xi = 1e-6; 3e-3 leaves room for the slip that starts at the edges)
kc.close(-creep[0]["fx"] / creep[0]["xi"], row["f11"], 3e-3, "initial slope = f11")
# large creepage: full slip, |Fx| -> mu Fn (measured 0.9958 at xi = 1e-2, 0.9995 at 3e-2)
kc.check(abs(creep[-1]["fx_mufn"]) > 0.99 and abs(creep[-1]["fx_mufn"]) <= 1 + 1e-12,
         f"saturation |Fx|/(mu Fn) = {abs(creep[-1]['fx_mufn']):.4f}")
kc.check(all(abs(a["fx"]) <= abs(b["fx"]) + 1e-9 for a, b in zip(creep, creep[1:])), "|Fx| grows with xi")

# the same case in a batch: its creep table is written as in a single run
with open(os.path.join(folder, "one.list"), "w") as f:
    f.write("wheel.nml\n")
os.remove(os.path.join(folder, "wheel.creep"))
import subprocess  # noqa: E402
proc = subprocess.run([kc.KCREEP, "--batch", "one.list"], cwd=folder, capture_output=True, text=True)
batch_creep = kc.read_table(os.path.join(folder, "wheel.creep")) if os.path.exists(os.path.join(folder, "wheel.creep")) else []
kc.check(proc.returncode == 0 and len(batch_creep) == len(creep) and
         all(abs(a["fx"] - b["fx"]) <= 1e-12 * abs(b["fx"]) + 1e-300 for a, b in zip(batch_creep, creep)),
         f"--batch runs &fastsim too: the same creep table ({proc.stderr.strip()[:200]})")

bad = "&patch semi_a = 1, semi_b = 1, mx = 20, my = 20 /\n&fastsim mu = 0.3, creepages = 1e-3 0 0, pressure = 'normal' /\n"
code, out, err, _ = kc.run(bad, folder, "bad", expect_ok=False)
kc.check(code == 2 and "pressure = 'normal'" in err and "gap" in err and len(err.strip().splitlines()) == 1,
         f"pressure = 'normal' without a gap refused in one line: {err.strip()}")
kc.check(not os.path.exists(os.path.join(folder, "bad.tab")) and not os.path.exists(os.path.join(folder, "bad.creep")),
         "nothing written")
kc.finish()
