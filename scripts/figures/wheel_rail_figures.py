#!/usr/bin/env python3
"""Figure of a &wheel_rail contact table (gnuplot), each patch its own line
(a patch is its kind, tread or flange, and its place among the patches of that
kind at the shift, from the field side; a line breaks where the patch is absent):
contact angle and reference point on the rail, the wheelset's rolling-radius
difference delta_r against the shift and its equivalent conicity lambda_eq
against the amplitude, C11 C22 C23 with their estimates.

  scripts/figures/wheel_rail_figures.py [TABLE.wr] [--out FOLDER] [--contact CSV]
      TABLE.wr   a table written by kcreep (default: build/output/s1002_uic60.wr,
                 made first by running build/kcreep input/s1002_uic60.nml there)
      --out      the folder for the PNG (default build/output)
      --contact  CONTACT's results as ../shared/contact-wr/s1002_uic60_base.csv
                 (columns shift_mm, yaw_rad, delta_rad, ycp_rail_mm, cksi): drawn as
                 points (yaw 0 rows; its angle's sign turned to kcreep's, its rolling
                 radius from CKSI: r = 460 (2 + CKSI) / (2 - CKSI), its creepage
                 referred to the mean of the two velocities; delta_r(y) = r(y) - r(-y)
                 and lambda_eq from those as below, where both y and -y are given)

delta_r and lambda_eq: from the wheelset table TABLE.ws beside TABLE.wr when it
exists (wheelset = .true.: the wheelset's own, Fn-weighted, docs/wheel_rail.md
"Wheelset"), drawn for shift >= 0, lambda_eq at the amplitude A = shift.
Without it delta_r(y) = r(y) - r(-y) from the table, r of the patch with the
largest vertical share fn cos(delta) at each shift, and lambda_eq from those:
b1 / (2 A), b1 the first harmonic of delta_r(A sin t), delta_r odd and linear
between the shifts (the .ws's definition, integrated exactly here).
Standard library and gnuplot only.

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


def conicity(amplitude, ys, dr):
    """lambda_eq = b1 / (2 A): b1 = (4 / pi) int_0^(pi/2) delta_r(A sin t) sin t dt for delta_r odd,
    linear between the shifts ys >= 0 (ys[0] = 0, dr[0] = 0): exact, segment by segment."""
    b1, t0 = 0.0, 0.0
    for k in range(len(ys) - 1):
        if ys[k] >= amplitude:
            break
        slope = (dr[k + 1] - dr[k]) / (ys[k + 1] - ys[k])
        a = dr[k] - slope * ys[k]                      # delta_r = a + slope y on this segment
        t1 = math.asin(min(1.0, ys[k + 1] / amplitude))
        b1 += a * (math.cos(t0) - math.cos(t1)) + slope * amplitude * (
            (t1 - math.sin(t1) * math.cos(t1)) - (t0 - math.sin(t0) * math.cos(t0))) / 2
        t0 = t1
    if t0 < math.pi / 2 - 1e-12:
        raise ValueError(f"delta_r is not given up to the amplitude {amplitude}")
    return 4 / math.pi * b1 / (2 * amplitude)


def wheelset_curves(radius_difference):
    """[(y, delta_r, lambda_eq at A = y)] for y > 0 from {y > 0: delta_r(y)}, delta_r(0) = 0."""
    radius_difference = {0.0: 0.0, **radius_difference}
    ys = sorted(radius_difference)
    dr = [radius_difference[y] for y in ys]
    return [(y, d, conicity(y, ys, dr)) for y, d in zip(ys, dr) if y > 0]


ws_path = os.path.splitext(path)[0] + ".ws"
if os.path.exists(ws_path):
    kcreep_ws = [(r["shift"], r["delta_r"], r["lambda_eq"]) for r in table.read(ws_path) if r["shift"] >= 0]
    source = "kcreep (.ws)"
else:
    def main_radius(s):
        at = [r for r in rows if r["shift"] == s]
        return max(at, key=lambda r: r["fn"] * math.cos(r["delta"]))["r_wheel"]
    kcreep_ws = wheelset_curves({s: main_radius(s) - main_radius(-s) for s in shifts
                                 if s > 0 and any(abs(t + s) < 1e-9 for t in shifts)})
    source = "kcreep (table)"
dr = os.path.join(work, "wheelset.dat")
with open(dr, "w") as f:
    f.writelines(f"{y} {d} {lam}\n" for y, d, lam in kcreep_ws)
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
        both = {s: r - radius[-s] for s, r in radius.items() if s > 0 and -s in radius}
        for y, d, lam in wheelset_curves(both):
            f.write(f"{y} {d} {lam}\n")
        f.write("\n\n")                                # kcreep's delta_r on CONTACT's shifts alone
        ours = {y: d for y, d, _ in kcreep_ws}
        if all(any(abs(y - t) < 1e-9 for t in ours) for y in both):
            for y, d, lam in wheelset_curves({y: d for y, d in ours.items() if any(abs(y - t) < 1e-9 for t in both)}):
                f.write(f"{y} {d} {lam}\n")
    points = cdat
png = os.path.join(out, os.path.splitext(os.path.basename(path))[0] + ".png")


def plot(col, title, extra=""):
    parts = [f'"{data}" index {k} u 1:{col}{extra} w {"yerrorlines" if extra else "lp"} pt 7 ps 0.4 '
             f't "{title} {n}"' for k, n in enumerate(names)]
    return ", ".join(parts)


contact_delta = f', "{points}" index 0 u 1:2 w p pt 6 ps 1.5 lc rgb "black" t "CONTACT"' if points else ""
contact_y = f', "{points}" index 0 u 1:3 w p pt 6 ps 1.5 lc rgb "black" t "CONTACT"' if points else ""
contact_dr = f', "{points}" index 1 u 1:2 w p pt 6 ps 1.5 lc rgb "black" t "CONTACT"' if points else ""
contact_lam = (f', "{points}" index 1 u 1:3 w p pt 6 ps 1.5 lc rgb "black" t "CONTACT", "{points}" index 2 '
               f'u 1:3 w p pt 2 ps 1.5 lc rgb "red" t "kcreep, CONTACT\'s shifts only"' if points else "")
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
set ylabel "wheelset delta_r = r_right - r_left [mm]"
plot "{dr}" u 1:2 w lp pt 7 ps 0.4 t "{source}"{contact_dr}
set xlabel "amplitude A [mm]"
set ylabel "equivalent conicity lambda_eq"
plot "{dr}" u 1:3 w lp pt 7 ps 0.4 t "{source}"{contact_lam}
set xlabel "lateral shift [mm]"
set ylabel "C11 (error bars: the estimates)"
plot {plot(7, "C11", ":($7*$10)")}
set ylabel "C22, C23"
plot {plot(8, "C22", ":($8*$11)")}, {plot(9, "C23", ":($9*$12)")}
unset multiplot
"""
try:
    subprocess.run(["gnuplot"], input=script, text=True, check=True)
finally:
    shutil.rmtree(work)
print(f"wrote {png}")
