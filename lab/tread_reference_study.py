#!/usr/bin/python3
"""The S1002 / UIC60 tread rows against references of their own (docs/wheel_rail.md,
"How far the tread rows' estimates hold"): each shift of input/s1002_uic60.nml run
alone at the default target, and again as a reference at target_error = 1e-5
with &solver cell_budget = 2,000,000 (normal grid 512 cells across the contact
area instead of 128, levels up to about 1,200 across instead of 96-196). The
reference stops `uncertain` at its budget; its own estimate is its uncertainty u.

Prints, per shift and coefficient, the default run's error against the
reference, its estimate and u; writes docs/data/tread_reference_study.dat and
the figure docs/figures/tread_reference_study.png.

  OMP_NUM_THREADS=1 flock /tmp/kcreep-bench.lock /usr/bin/python3 lab/tread_reference_study.py
  ... --stored    the references kept in docs/data/tread_reference_study.dat (made
                  on staircase levels before kcreep's levels had a blended edge:
                  an independent discretisation), the default runs only

Needs ../shared/profiles beside the repository and matplotlib (Debian's
python3-matplotlib); about 2 minutes and 4 GB per reference on one core.
"""
import argparse
import os
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
DEFAULT_BUDGET = 160000
REFERENCE_BUDGET, REFERENCE_TARGET = 2000000, 1e-5


def arguments():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--kcreep", default=os.path.join(ROOT, "build", "kcreep"))
    p.add_argument("--shifts", default="-3,0,3,5,6", help="lateral shifts in mm (comma-separated)")
    p.add_argument("--no-write", action="store_true", help="print only; leave docs/ alone")
    p.add_argument("--plot-only", action="store_true", help="redraw the figure from docs/data/tread_reference_study.dat")
    p.add_argument("--stored", action="store_true",
                   help="take the references (value, u, wall time) from docs/data/tread_reference_study.dat")
    return p.parse_args()


def plot(dat):
    """Per shift and coefficient: the default run's |error| against its estimate, with u as the error's bar."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    rows = [line.split() for line in open(dat) if not line.startswith("#")]
    fig, axes = plt.subplots(1, 3, figsize=(12, 3.6), sharey=True)
    for ax, (k, name) in zip(axes, enumerate(("C11", "C22", "C23"))):
        x = range(len(rows))
        error = [100 * abs(float(r[1 + 4 * k])) for r in rows]
        estimate = [100 * float(r[2 + 4 * k]) for r in rows]
        u = [100 * float(r[3 + 4 * k]) for r in rows]
        ax.bar(x, error, yerr=u, capsize=3, color="tab:blue", alpha=0.6, label="|error| against the reference (bar: its u)")
        ax.plot(x, estimate, "v", color="tab:red", label="the default run's estimate")
        ax.axhline(100 * (3e-3 if k == 2 else 1e-3), color="grey", lw=0.8, ls="--", label="target")
        ax.set_xticks(list(x))
        ax.set_xticklabels([f"{float(r[0]):+g}" for r in rows])
        ax.set_xlabel("lateral shift (mm)")
        ax.set_title(name)
    axes[0].set_ylabel("relative error (%)")
    axes[0].legend(fontsize=7)
    fig.suptitle("S1002 / UIC60 tread rows alone, default target, against references at 1e-5 "
                 "(2 million cells, normal grid 512 across)", fontsize=9)
    fig.tight_layout()
    png = os.path.join(ROOT, "docs", "figures", "tread_reference_study.png")
    fig.savefig(png, dpi=110)
    return png


def stored_references(dat):
    """shift -> ({c11, c22, c23, err11, err22, err23}, wall s) of the references kept in dat."""
    refs = {}
    for line in open(dat):
        if line.startswith("#"):
            continue
        v = line.split()
        ref = {}
        for k, c in enumerate(("11", "22", "23")):
            ref["err" + c] = float(v[3 + 4 * k])
            ref["c" + c] = float(v[4 + 4 * k])
        refs[int(v[0])] = (ref, float(v[15]))
    return refs


def main():
    args = arguments()
    dat = os.path.join(ROOT, "docs", "data", "tread_reference_study.dat")
    if args.plot_only:
        print(f"wrote {os.path.relpath(plot(dat), ROOT)}")
        return
    sys.path.insert(0, HERE)
    from flange_budget_study import run   # one shift alone, its .wr row
    stored = stored_references(dat) if args.stored else {}
    lines = []
    with tempfile.TemporaryDirectory() as work:
        for shift in (int(s) for s in args.shifts.split(",")):
            row, wall = run(os.path.abspath(args.kcreep), work, shift, DEFAULT_BUDGET)
            if args.stored:
                ref, ref_wall = stored[shift]
            else:
                ref, ref_wall = run(os.path.abspath(args.kcreep), work, shift, REFERENCE_BUDGET, REFERENCE_TARGET)
            cells = [f"{shift}"]
            text = []
            for c in ("11", "22", "23"):
                error = row["c" + c] / ref["c" + c] - 1
                cells += [f"{error:.3e}", f"{row['err' + c]:.3e}", f"{ref['err' + c]:.3e}", f"{ref['c' + c]:.7f}"]
                text.append(f"C{c} {100 * error:+.4f} % (est {100 * row['err' + c]:.3f} %, u {100 * ref['err' + c]:.4f} %)")
            cells += [row["verdict"], f"{wall:.1f}", f"{ref_wall:.1f}"]
            lines.append(" ".join(cells))
            print(f"shift {shift:+3d}  {row['verdict']:9s} " + "  ".join(text) + f"  {wall:.1f} s / {ref_wall:.0f} s",
                  flush=True)
    if args.no_write:
        return
    with open(dat, "w") as f:
        f.write("# lab/tread_reference_study.py: S1002 / UIC60 rows alone, default target, against\n"
                f"# references at target_error {REFERENCE_TARGET:g}, cell_budget {REFERENCE_BUDGET} "
                "(on staircase levels: kcreep before its levels' blended edge)\n"
                "# shift_mm then per C11 C22 C23: error(rel) estimate(rel) u_ref(rel) ref_value; "
                "verdict wall_s ref_wall_s\n")
        f.write("\n".join(lines) + "\n")
    png = plot(dat)
    print(f"wrote {os.path.relpath(dat, ROOT)} and {os.path.relpath(png, ROOT)}")


if __name__ == "__main__":
    main()
