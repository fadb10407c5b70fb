"""&wheel_rail profiles: implausible ones refused, measured ones smoothed.

- Refused with exit 2 and one line naming the file and line or value, no
  table written: a point that goes back in y, a vertical step, a MiniProf
  rail (.ban) given as the wheel and a wheel (.whl) as the rail, a plain
  wheel file with z up, the flange on the field side (wrong wheel_mirror),
  a rail whose contact reaches its last point.
- Automatic smoothing (no smoothing line): exact profiles keep the
  interpolating spline; the same circles written to 0.01 mm (MiniProf's
  resolution) or with 0.005 mm of noise are smoothed and give the exact
  profiles' C11 within 2 %; the measured
  worn MiniProf pair of ../shared/profiles gives an `ok` row within 2 % of
  its table with smoothing = 10.
Small profiles written here, one shift each, target_error 1e-2.

usage: test_wheel_rail_profiles.py KCREEP SOURCE_DIR
"""
import math
import os
import random
import re
import sys

import kctest as kc

folder = kc.setup()
source = os.path.abspath(sys.argv[2])
profiles = os.path.abspath(os.path.join(source, "..", "shared", "profiles"))


def arc(radius, lo, hi, convex_down, step=0.25, digits=10):
    """(y, z) of a circular arc touching z = 0 at y = 0 (z down), y from lo to hi."""
    n = int(round((hi - lo) / step))
    pts = []
    for k in range(n + 1):
        y = lo + k * step
        z = radius - math.sqrt(radius * radius - y * y)
        pts.append((round(y, digits), round(-z if convex_down else z, digits)))
    return pts


def text(pts):
    return "".join(f"{y:.10f} {z:.12f}\n" for y, z in pts)


def c11_of(name):
    rows = kc.read_table(os.path.join(folder, name + ".wr"))
    return float(rows[0]["c11"]) if len(rows) == 1 else float("nan")


def header_smoothing(name):
    with open(os.path.join(folder, name + ".wr")) as f:
        m = re.search(r"smoothing (.*)", f.read())
    return m.group(1) if m else ""


wheel = arc(300, -40, 40, True)
rail = arc(300, -35, 35, False)
files = {"wheel.dat": text(wheel), "rail.dat": text(rail)}
# a point 1 mm back in y (file line 61), a 3 mm step in z after y = 10 (line 182)
back = rail[:60] + [(rail[59][0] - 1.0, rail[59][1])] + rail[60:]
files["back.dat"] = text(back)
files["step.dat"] = text([(y, z + (3.0 if y > 10 else 0.0)) for y, z in rail])
# MiniProf files (no header: the first line is numbers; Y up)
files["wheel.ban"] = "".join(f"{y:.4f} {-z:.4f}\n" for y, z in wheel)
files["rail.whl"] = "".join(f"{y:.4f} {-z:.4f}\n" for y, z in rail)
files["wheel_up.dat"] = text([(y, -z) for y, z in wheel])
# a flanged wheel: the tread arc with a 10 mm flange at y = -47, beyond the rail's end
flanged = [(y, z + 10 * math.exp(-((y + 47) / 3) ** 2)) for y, z in arc(300, -55, 40, True)]
files["flanged.dat"] = text(flanged)
# a rail measured only up to y = 0.5: the contact at its crown reaches its last point
files["rail_cut.dat"] = text([(y, z) for y, z in rail if y <= 0.5])
# the circles written to 0.01 mm, as a MiniProf file is
files["wheel_q.dat"] = text([(round(y, 2), round(z, 2)) for y, z in wheel])
files["rail_q.dat"] = text([(round(y, 2), round(z, 2)) for y, z in rail])
# the circles with Gaussian noise of 0.005 mm in y and z (a fixed seed)
rng = random.Random(46)
files["wheel_n.dat"] = text([(y + rng.gauss(0, 0.005), z + rng.gauss(0, 0.005)) for y, z in wheel])
files["rail_n.dat"] = text([(y + rng.gauss(0, 0.005), z + rng.gauss(0, 0.005)) for y, z in rail])
for name, body in files.items():
    with open(os.path.join(folder, name), "w") as f:
        f.write(body)

place = "flange_back_position = -72.5"
tail = "&material g = 82000, nu = 0.28 /\n&solver target_error = 1e-2 /\n"


def run(name, wheel_file, rail_file, extra=""):
    return kc.run(f"&wheel_rail wheel_file = '{wheel_file}', rail_file = '{rail_file}', {place},\n"
                  f"  shifts = 0, vertical_force = 80000 {extra} /\n" + tail, folder, name, expect_ok=False)


# 1. refused: exit 2, one line naming the file and the line or value, nothing written
cases = [
    ("back", "wheel.dat", "back.dat", "", ["rail_file", "back.dat", "line 61", "goes back"]),
    ("step", "wheel.dat", "step.dat", "", ["rail_file", "step.dat", "line 182", "vertical step"]),
    ("ban_as_wheel", "wheel.ban", "rail.dat", "", ["wheel_file", "wheel.ban", "(.ban) given as the wheel"]),
    ("whl_as_rail", "wheel.dat", "rail.whl", "", ["rail_file", "rail.whl", "(.whl) given as the rail"]),
    ("wheel_z_up", "wheel_up.dat", "rail.dat", "", ["wheel_file", "wheel_up.dat", "z seems to point upwards"]),
    ("flange_field_side", "flanged.dat", "rail.dat", ", wheel_mirror = .true.",
     ["wheel_file", "flanged.dat", "wheel_mirror = .true.", "field side"]),
    ("rail_end", "wheel.dat", "rail_cut.dat", "", ["rail_file", "rail_cut.dat", "reaches the end", "shift = 0"]),
]
for name, w, r, extra, fragments in cases:
    code, out, err, _ = run(name, w, r, extra)
    lines = [l for l in err.strip().splitlines() if l]
    kc.check(code == 2 and len(lines) == 1, f"{name}: refused with exit 2 and one line (exit {code}): {err.strip()}")
    missing = [f for f in fragments if f not in err]
    kc.check(not missing, f"{name}: the message names {missing}: {err.strip()}")
    kc.check(not os.path.exists(os.path.join(folder, name + ".wr")), f"{name}: nothing written")

# the same flanged wheel the right way round runs
code, out, err, _ = run("flange_gauge_side", "flanged.dat", "rail.dat")
kc.check(code == 0, "a flanged wheel with its flange on the gauge side runs" + ("" if code == 0 else ": " + err.strip()))

# 2. automatic smoothing: exact circles keep the interpolating spline; the
# same circles at 0.01 mm are smoothed back to the exact circles' C11
code, out, err, _ = run("exact", "wheel.dat", "rail.dat")
kc.check(code == 0, "exact circles run" + ("" if code == 0 else ": " + err.strip()))
exact = c11_of("exact") if code == 0 else float("nan")
if code == 0:
    kc.check(header_smoothing("exact").startswith("automatic (wheel 0.0, rail 0.0 "),
             f"exact profiles are not smoothed: {header_smoothing('exact')}")
code, out, err, _ = run("quantised", "wheel_q.dat", "rail_q.dat")
kc.check(code == 0, "circles at 0.01 mm run" + ("" if code == 0 else ": " + err.strip()))
if code == 0:
    c11 = c11_of("quantised")
    verdict = kc.read_table(os.path.join(folder, "quantised.wr"))[0]["verdict"]
    lam = re.findall(r"wheel ([-+0-9.Ee]+), rail ([-+0-9.Ee]+)", header_smoothing("quantised"))
    kc.check(len(lam) == 1 and all(float(v) > 0 for v in lam[0]),
             f"circles at 0.01 mm are smoothed: {header_smoothing('quantised')}")
    # measured: 5.348 against the exact 5.300 (+0.9 %; smoothing = 0.1: +0.3 %, 10: +0.6 %):
    # rounded to 0.01 mm the crown is flat over 3.5 mm, a long wave no smoothing restores
    kc.check(abs(c11 / exact - 1) < 0.02 and verdict == "ok",
             f"circles at 0.01 mm, smoothed: C11 {c11} against the exact {exact} within 2 %, verdict {verdict}")
# the rounding matters: the interpolating spline gives three patches (the main one's C11 7.46, +41 %)
code, out, err, _ = run("quantised_raw", "wheel_q.dat", "rail_q.dat", ", smoothing = 0")
if code == 0:
    raw = kc.read_table(os.path.join(folder, "quantised_raw.wr"))
    kc.check(len(raw) != 1 or abs(float(raw[0]["c11"]) / exact - 1) > 0.1,
             f"circles at 0.01 mm, smoothing = 0: {len(raw)} patches, far from the exact circles' one")

# noisy circles: measured C11 5.378 against the exact 5.300 with this seed (+1.5 %),
# -1.3 to +0.8 % with seeds 1-7; unsmoothed 12.3 (uncertain) on another realisation
code, out, err, _ = run("noisy", "wheel_n.dat", "rail_n.dat")
kc.check(code == 0, "circles with noise run" + ("" if code == 0 else ": " + err.strip()))
if code == 0:
    c11 = c11_of("noisy")
    kc.check(abs(c11 / exact - 1) < 0.02, f"circles with 0.005 mm noise, smoothed: C11 {c11} against {exact} within 2 %")

# 3. the measured worn pair as given (no smoothing line) against smoothing = 10
if os.path.isdir(profiles):
    worn = (f"&wheel_rail wheel_file = '{profiles}/avg_wheel.whl', rail_file = '{profiles}/avg_HR.BAN', "
            "rail_mirror = .true.,\n  gauge_width = 1435.1, gauge_height = 15.875, flange_back_distance = 1352.2, "
            "flange_back_position = 0, nominal_radius = 419.1, shifts = 0, vertical_force = 70000")
    c = {}
    for name, extra in (("worn_auto", ""), ("worn_10", ", smoothing = 10")):
        code, out, err, _ = kc.run(worn + extra + " /\n" + tail, folder, name, expect_ok=False)
        kc.check(code == 0, f"{name} runs" + ("" if code == 0 else ": " + err.strip()))
        if code == 0:
            row = kc.read_table(os.path.join(folder, name + ".wr"))[0]
            c[name] = float(row["c11"])
            kc.check(row["verdict"] == "ok", f"{name}: verdict {row['verdict']}")
    if len(c) == 2:
        # measured (docs/wheel_rail.md "Measured profiles"): 4.891 against 4.915 at shift 0;
        # without smoothing 7.47 (uncertain)
        kc.check(abs(c["worn_auto"] / c["worn_10"] - 1) < 0.02,
                 f"worn pair as given: C11 {c['worn_auto']} within 2 % of smoothing = 10's {c['worn_10']}")
else:
    kc.check(False, f"../shared/profiles missing ({profiles})")
kc.finish()
