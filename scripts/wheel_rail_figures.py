#!/usr/bin/env python3
"""Figure of a &wheel_rail contact table (gnuplot): the placed profiles are not
in the table, so the left panel shows the contact points on each profile
(y_rail, y_wheel) against the shift with the contact angle; the right panels
the patch sizes, C11 C22 C23 with their error bars, and the rolling radius.

  scripts/wheel_rail_figures.py [TABLE.wr] [--out FOLDER]
      TABLE.wr  a table written by kcreep (default: build/output/s1002_uic60.wr,
                made first by running build/kcreep input/s1002_uic60.nml there)
      --out     the folder for the PNG (default build/output)

Standard library and gnuplot only.

    scripts/wheel_rail_figures.py --help    this text
"""
import os
import subprocess
import sys

if any(a in ("-h", "--help") for a in sys.argv[1:]):
    print(__doc__.strip())
    sys.exit(0)

here = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(here, "python", "kcreep"))
import table  # noqa: E402  (python/kcreep/table.py, standard library only)

args = sys.argv[1:]
out = os.path.join(here, "build", "output")
if "--out" in args:
    k = args.index("--out")
    out = os.path.abspath(args[k + 1])
    del args[k:k + 2]
os.makedirs(out, exist_ok=True)
if args:
    path = os.path.abspath(args[0])
else:
    path = os.path.join(out, "s1002_uic60.wr")
    subprocess.run([os.path.join(here, "build", "kcreep"), os.path.join(here, "input", "s1002_uic60.nml")],
                   cwd=out, check=True, stdout=subprocess.DEVNULL)
rows = table.read(path)
data = os.path.join(out, os.path.basename(path) + ".dat")
with open(data, "w") as f:
    for r in rows:
        f.write(" ".join(str(r[c]) for c in ("shift", "patch", "y_rail", "y_wheel", "delta", "r_wheel", "length",
                                            "width", "c11", "c22", "c23", "err11", "err22", "err23")) + "\n")
png = os.path.join(out, os.path.splitext(os.path.basename(path))[0] + ".png")
script = f"""
set terminal pngcairo size 1200,900 font ",10" noenhanced
set output "{png}"
set multiplot layout 2,2 title "{os.path.basename(path)}"
set grid
set xlabel "lateral shift [mm]"
set ylabel "contact point [mm]"
set y2label "contact angle [rad]"
set y2tics
plot "{data}" u 1:3 w lp t "y_rail", "" u 1:4 w lp t "y_wheel", "" u 1:5 axes x1y2 w lp t "delta"
unset y2tics; unset y2label
set ylabel "patch size [mm]"
plot "{data}" u 1:7 w lp t "length (x)", "" u 1:8 w lp t "width (s)"
set ylabel "C11 C22 C23 (error bars: the estimates)"
plot "{data}" u 1:9:($9*$12) w yerrorlines t "C11", "" u 1:10:($10*$13) w yerrorlines t "C22", \\
     "" u 1:11:($11*$14) w yerrorlines t "C23"
set ylabel "rolling radius [mm]"
plot "{data}" u 1:6 w lp t "r_wheel"
unset multiplot
"""
subprocess.run(["gnuplot"], input=script, text=True, check=True)
print(f"wrote {png}")
