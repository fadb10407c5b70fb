#!/usr/bin/env python3
"""Figure of a &wheel_rail contact table (gnuplot), each patch its own line
(a patch is its kind, tread or flange, and its place among the patches of that
kind at the shift, from the field side; a line breaks where the patch is absent):
contact angle and reference point on the rail, the rolling-radius difference of a
symmetric wheelset Delta r(y) = r(y) - r(-y), C11 C22 C23 with their estimates,
and the patch sizes, all against the lateral shift.

  scripts/figures/wheel_rail_figures.py [TABLE.wr] [--out FOLDER] [--contact CSV]
      TABLE.wr   a table written by kcreep (default: build/output/s1002_uic60.wr,
                 made first by running build/kcreep input/s1002_uic60.nml there)
      --out      the folder for the PNG (default build/output)
      --contact  CONTACT's results as ../shared/contact-wr/s1002_uic60_base.csv
                 (columns shift_mm, yaw_rad, delta_rad, ycp_rail_mm, cksi): drawn as
                 points (yaw 0 rows; its angle's sign turned to kcreep's, its rolling
                 radius from CKSI: r = 460 (2 + CKSI) / (2 - CKSI), its creepage
                 referred to the mean of the two velocities)

Delta r takes at each shift the radius of the patch with the largest vertical
share fn cos(delta). Standard library and gnuplot only.

    scripts/figures/wheel_rail_figures.py --help    this text
"""
import csv
import math
import os
import shutil
import subprocess
import sys
import tempfile

if any(a in ("-h", "--help") for a in sys.argv[1:]):
    print(__doc__.strip())
    sys.exit(0)

here = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(here, "python"))
from kcreep import table  # noqa: E402  (python/kcreep/table.py, standard library only)


def option(args, name):
    if name not in args:
        return None
    k = args.index(name)
    if k + 1 >= len(args):
        sys.exit(f"wheel_rail_figures.py: error: {name} needs a value (see --help)")
    value = args[k + 1]
    del args[k:k + 2]
    return value


args = sys.argv[1:]
out = os.path.abspath(option(args, "--out") or os.path.join(here, "build", "output"))
contact = option(args, "--contact")
os.makedirs(out, exist_ok=True)
if args:
    path = os.path.abspath(args[0])
else:
    path = os.path.join(out, "s1002_uic60.wr")
    subprocess.run([os.path.join(here, "build", "kcreep"), os.path.join(here, "input", "s1002_uic60.nml")],
                   cwd=out, check=True, stdout=subprocess.DEVNULL)
rows = table.read(path)
shifts = sorted({r["shift"] for r in rows})
step = min((b - a for a, b in zip(shifts, shifts[1:])), default=1.0)

# each patch's line: (kind, place among that kind's patches at the shift, field side first)
lines = {}
for s in shifts:
    at = [r for r in rows if r["shift"] == s]          # the table's order: field side first
    for kind in ("tread", "flange"):
        for place, r in enumerate(x for x in at if x.get("kind", "tread") == kind):
            lines.setdefault((kind, place + 1), []).append(r)
work = tempfile.mkdtemp()                               # the plotted data, removed at the end
data = os.path.join(work, "patches.dat")
columns = ("shift", "delta", "y_rail", "r_wheel", "length", "width", "c11", "c22", "c23", "err11", "err22", "err23")
names = []
with open(data, "w") as f:
    for (kind, place), patch in sorted(lines.items()):
        names.append(kind if place == 1 else f"{kind} {place}")
        previous = None
        for r in patch:
            if previous is not None and r["shift"] - previous > 1.5 * step:
                f.write("\n")                           # absent in between: the line breaks
            f.write(" ".join(str(r[c]) for c in columns) + "\n")
            previous = r["shift"]
        f.write("\n\n")


def main_radius(s):
    at = [r for r in rows if r["shift"] == s]
    return max(at, key=lambda r: r["fn"] * math.cos(r["delta"]))["r_wheel"] if at else None


dr = os.path.join(work, "radius_difference.dat")
with open(dr, "w") as f:
    for s in shifts:
        if s >= 0 and any(abs(t + s) < 1e-9 for t in shifts):
            f.write(f"{s} {main_radius(s) - main_radius(-s)}\n")
points = ""
if contact:
    ref = [r for r in csv.DictReader(open(contact)) if float(r["yaw_rad"]) == 0]
    radius = {}
    cdat = os.path.join(work, "contact.dat")
    with open(cdat, "w") as f:
        for r in ref:
            c = float(r["cksi"])
            radius[float(r["shift_mm"])] = 460 * (2 + c) / (2 - c)
            f.write(f"{r['shift_mm']} {-float(r['delta_rad'])} {r['ycp_rail_mm']}\n")
        f.write("\n\n")
        for s, r in sorted(radius.items()):
            if s > 0 and -s in radius:
                f.write(f"{s} {r - radius[-s]}\n")
    points = cdat
png = os.path.join(out, os.path.splitext(os.path.basename(path))[0] + ".png")


def plot(col, title, extra=""):
    parts = [f'"{data}" index {k} u 1:{col}{extra} w {"yerrorlines" if extra else "lp"} pt 7 ps 0.4 '
             f't "{title} {n}"' for k, n in enumerate(names)]
    return ", ".join(parts)


contact_delta = f', "{points}" index 0 u 1:2 w p pt 6 ps 1.5 lc rgb "black" t "CONTACT"' if points else ""
contact_y = f', "{points}" index 0 u 1:3 w p pt 6 ps 1.5 lc rgb "black" t "CONTACT"' if points else ""
contact_dr = f', "{points}" index 1 u 1:2 w p pt 6 ps 1.5 lc rgb "black" t "CONTACT"' if points else ""
script = f"""
set terminal pngcairo size 1200,1200 font ",10" noenhanced
set output "{png}"
set multiplot layout 3,2 title "{os.path.basename(path)}"
set grid
set key left top
set xlabel "lateral shift [mm]"
set ylabel "contact angle delta [rad]"
plot {plot(2, "delta")}{contact_delta}
set ylabel "reference point on the rail y_rail [mm]"
set key right top
plot {plot(3, "y_rail")}{contact_y}
set key left top
set ylabel "r(y) - r(-y) [mm] (patch of largest fn cos(delta))"
plot "{dr}" u 1:2 w lp pt 7 ps 0.4 t "kcreep"{contact_dr}
set ylabel "C11 (error bars: the estimates)"
plot {plot(7, "C11", ":($7*$10)")}
set ylabel "C22, C23"
plot {plot(8, "C22", ":($8*$11)")}, {plot(9, "C23", ":($9*$12)")}
set ylabel "patch size [mm]"
plot {plot(5, "length")}, {plot(6, "width")}
unset multiplot
"""
try:
    subprocess.run(["gnuplot"], input=script, text=True, check=True)
finally:
    shutil.rmtree(work)
print(f"wrote {png}")
