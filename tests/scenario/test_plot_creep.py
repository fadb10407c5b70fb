"""scripts/plot_creep.sh (defect 9, second half): the creep curves are drawn
against the creepage, not a point index or the linear theory's force, and
with combined creepage -Fx and -Fy sit in separate panels. Checked on what
the script hands gnuplot (--keep FOLDER): the data columns and creep.gp.

    test_plot_creep.py PATH/TO/kcreep
"""
import os
import shutil
import subprocess
import kctest as kc

folder = kc.setup()
script = os.path.join(kc.REPO, "scripts", "plot_creep.sh")
if not shutil.which("gnuplot"):
    kc.check(False, "gnuplot installed (scripts/setup.sh installs it)")
    kc.finish()


def plot(name, creepages, sweep):
    with open(os.path.join(folder, name + ".nml"), "w") as f:
        f.write("&patch semi_a=1, semi_b=0.6, mx=12, my=12 /\n"
                f"&fastsim mu=0.3, creepages = {creepages},\n{sweep} /\n")
    run = subprocess.run([kc.KCREEP, name + ".nml"], cwd=folder, capture_output=True, text=True, timeout=60)
    kc.check(run.returncode == 0, f"{name}: kcreep ran ({run.stderr.strip()[-200:]})")
    keep = os.path.join(folder, name + ".keep")
    os.makedirs(keep)
    drawn = subprocess.run([script, name + ".creep", "--keep", keep], cwd=folder, capture_output=True,
                           text=True, timeout=60)
    kc.check(drawn.returncode == 0 and os.path.getsize(os.path.join(folder, name + "_creep.png")) > 0,
             f"{name}: plot_creep.sh drew {name}_creep.png ({drawn.stderr.strip()[-300:]})")
    creep = []
    for line in open(os.path.join(folder, name + ".creep")):
        if not line.startswith("#") and line.strip():
            w = line.split()
            creep.append(tuple(float(v) for v in w[:3]))
    data = []
    for line in open(os.path.join(keep, "exact.dat")):
        if not line.startswith("#") and line.strip():
            data.append([float(v) for v in line.split()])
    return creep, data, open(os.path.join(keep, "creep.gp")).read()


def close(a, b):
    return abs(a - b) <= 1e-5 * max(abs(a), abs(b))


# pure creepages: a sweep in xi, points in eta and phi; one panel
creep, data, gp = plot("pure", "0 1e-3 0, 0 0 2e-3",
                       "sweep_direction = 1 0 0, sweep_from = 1e-5, sweep_to = 1e-2, sweep_points = 6, "
                       "sweep_spacing = 'log'")
kc.check(len(data) == len(creep), f"pure: one plotted point per row of the creep table ({len(data)})")
x = [d[0] for d in data]
expected = [max(abs(v) for v in c) for c in creep]
kc.check(all(close(a, b) for a, b in zip(x, expected)),
         f"pure: the x column is the creepage (xi, eta or phi of each point): {x}")
kc.check(all(close(d[0], c[0]) for d, c in zip(data[2:], creep[2:])), "pure: the sweep's x is its xi")
kc.check("plot '" in gp and "u 1:" in gp and "multiplot" not in gp,
         "pure creepage: one panel, x from the creepage column")
xlabel = [l for l in gp.splitlines() if l.startswith("set xlabel")]
kc.check(xlabel and all(w in xlabel[0] for w in ("xi", "eta", "phi")) and "f11" not in xlabel[0],
         f"pure: the x axis is named by the creepages it shows ({xlabel})")
kc.check("set logscale x" in gp, "pure: the sweep's three decades on a log axis")

# combined creepage: Fx and Fy in two panels against the creepage
creep, data, gp = plot("combined", "1e-3 0 0, 5e-4 1e-3 0, 2e-4 -3e-4 0", "")
kc.check([round(d[0], 12) for d in data] == [1e-3, 1e-3, 3e-4],
         f"combined: x is each point's largest creepage component ({[d[0] for d in data]})")
kc.check(all(close(d[4], c[0]) and close(d[5], c[1]) for d, c in zip(data, creep)),
         "combined: the data carry xi and eta beside the plotted values")
kc.check("set multiplot layout 2,1" in gp, "combined creepage: two panels")
plots = [l for l in gp.splitlines() if l.startswith("plot ")]
kc.check(len(plots) == 2 and "u 1:2 " in plots[0] and "u 1:3 " in plots[1]
         and "-Fx" in plots[0] and "-Fy" in plots[1],
         f"combined: -Fx in the first panel, -Fy in the second ({len(plots)} plot commands)")
kc.finish()
