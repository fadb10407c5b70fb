#!/usr/bin/python3
"""The S1002 / UIC60 flange rows against the cell budget (docs/wheel_rail.md,
"The flange rows' ladders"): each shift of input/s1002_uic60.nml run alone at
the default target with &solver cell_budget = 160,000 (the default, where the
budget scales a flange strip's base levels below 56 cells across), 320,000 and
640,000. Prints C11, C22, C23, their estimates, the verdict and the wall time
per run; writes the numbers to lab/data/flange_budget_study.dat and the
figure lab/figures/flange_budget_study.png (C11 with its error bar against
the budget, one panel per shift).

  OMP_NUM_THREADS=1 flock /tmp/kcreep-bench.lock /usr/bin/python3 lab/flange_budget_study.py

Needs ../shared/profiles beside the repository and matplotlib (Debian's
python3-matplotlib); about 3 minutes on one core.
"""
import argparse
import os
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def arguments():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--kcreep", default=os.path.join(ROOT, "build", "kcreep"))
    p.add_argument("--shifts", default="7,8,10", help="lateral shifts in mm (comma-separated)")
    p.add_argument("--budgets", default="160000,320000,640000", help="&solver cell_budget values")
    p.add_argument("--no-write", action="store_true", help="print only; leave docs/ alone")
    p.add_argument("--plot-only", action="store_true", help="redraw the figure from lab/data/flange_budget_study.dat")
    return p.parse_args()


def run(kcreep, work, shift, budget, target=None):
    """One shift at one budget (and target_error, if given): (row of the .wr table as a dict, wall seconds)."""
    sys.path.insert(0, os.path.join(ROOT, "python"))
    from kcreep import table
    profiles = os.path.abspath(os.path.join(ROOT, "..", "shared", "profiles"))
    name = f"s{shift}_b{budget}" + ("" if target is None else f"_t{target:g}")
    solver = f"cell_budget = {budget}" + ("" if target is None else f", target_error = {target:g}")
    with open(os.path.join(work, name + ".nml"), "w") as f:
        f.write(f"&wheel_rail wheel_file = '{profiles}/MBench_S1002_v3.prw',\n"
                f"  rail_file = '{profiles}/MBench_UIC60_v3.prr', shifts = {shift}, vertical_force = 80000 /\n"
                f"&material g = 82000, nu = 0.28 /\n&solver {solver} /\n")
    start = time.perf_counter()
    proc = subprocess.run([kcreep, name + ".nml"], cwd=work, capture_output=True, text=True)
    wall = time.perf_counter() - start
    if proc.returncode != 0:
        sys.exit(f"kcreep failed on shift {shift}, budget {budget}: {proc.stderr.strip()}")
    return table.read(os.path.join(work, name + ".wr"))[0], wall


def plot(dat):
    """The figure from the data file: C11 with its error bar against the budget, a panel per shift."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    rows = [line.split() for line in open(dat) if not line.startswith("#")]
    shifts = sorted({int(r[0]) for r in rows})
    fig, axes = plt.subplots(1, len(shifts), figsize=(4 * len(shifts), 3.4), squeeze=False)
    for ax, shift in zip(axes[0], shifts):
        mine = [r for r in rows if int(r[0]) == shift]
        x = [int(r[1]) / 1000 for r in mine]
        c11 = [float(r[2]) for r in mine]
        ax.errorbar(x, c11, yerr=[c * float(r[5]) for c, r in zip(c11, mine)], fmt="o", capsize=4)
        ax.set_xscale("log")
        ax.minorticks_off()
        ax.set_xticks(x)
        ax.set_xticklabels([f"{v:g}k" for v in x])
        ax.set_xlim(min(x) / 1.4, max(x) * 1.4)
        ax.set_title(f"shift +{shift} mm")
        ax.set_xlabel("cell budget")
        ax.set_ylabel("C11 with its estimated error")
    fig.suptitle("S1002 / UIC60 flange rows: at the default budget (160k) the levels are scaled below 56 across",
                 fontsize=9)
    fig.tight_layout()
    png = os.path.join(ROOT, "lab", "figures", "flange_budget_study.png")
    fig.savefig(png, dpi=110)
    return png


def main():
    args = arguments()
    dat = os.path.join(ROOT, "lab", "data", "flange_budget_study.dat")
    if args.plot_only:
        print(f"wrote {os.path.relpath(plot(dat), ROOT)}")
        return
    shifts = [int(s) for s in args.shifts.split(",")]
    budgets = [int(b) for b in args.budgets.split(",")]
    rows = []
    with tempfile.TemporaryDirectory() as work:
        for shift in shifts:
            for budget in budgets:
                row, wall = run(os.path.abspath(args.kcreep), work, shift, budget)
                rows.append((shift, budget, row, wall))
                print(f"shift {shift:3d}  budget {budget:7d}  C11 {row['c11']:.4f} C22 {row['c22']:.4f} "
                      f"C23 {row['c23']:.4f}  estimates {100 * row['err11']:.3f} / {100 * row['err22']:.3f} / "
                      f"{100 * row['err23']:.3f} %  {row['verdict']}  {wall:.1f} s", flush=True)
    if args.no_write:
        return
    with open(dat, "w") as f:
        f.write("# lab/flange_budget_study.py: S1002 / UIC60 rows alone at the default target\n")
        f.write("# shift_mm cell_budget c11 c22 c23 err11 err22 err23 verdict wall_s\n")
        for shift, budget, row, wall in rows:
            f.write(f"{shift} {budget} {row['c11']:.6f} {row['c22']:.6f} {row['c23']:.6f} {row['err11']:.3e} "
                    f"{row['err22']:.3e} {row['err23']:.3e} {row['verdict']} {wall:.1f}\n")
    png = plot(dat)
    print(f"wrote {os.path.relpath(dat, ROOT)} and {os.path.relpath(png, ROOT)}")


if __name__ == "__main__":
    main()
