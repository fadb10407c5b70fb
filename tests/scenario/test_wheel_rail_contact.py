"""&wheel_rail against CONTACT's module 1 on S1002 / UIC60 (70 kN, right wheel):
 - the nine shifts and two yawed rows of ../shared/contact-wr/s1002_uic60_base.csv:
   the same patch count; the reference point on the rail (y_rail) and the
   contact angle (interpenetration centre of gravity, weighted mean angle) within
   0.3 mm / 0.005 rad on the tread and 1 mm / 0.03 rad on the flange, the rolling
   radius (CONTACT's: 460 (2 + CKSI) / (2 - CKSI)) within 0.03 / 0.5 mm, and
   the vertical share fn cos(delta) within 1 / 3 % of the load of CONTACT's
   FN cos(delta) + FS sin(delta) (kcreep's table is frictionless);
 - continuity: every 0.1 mm over 0.0-0.5, 4.8-5.3 and 6.5-7.0 mm (where the
   clearance minimum jumped: 0.2 -> 0.3 mm from y_rail -8.07 to -18.41 mm) against
   CONTACT's runs at the same shifts (tests/data/contact_s1002_uic60_steps.csv):
   the same values as above, and no step of the angle between neighbours larger
   than twice CONTACT's largest step in that range.
Coefficients are not under test here: target_error = 1e-2.

usage: test_wheel_rail_contact.py KCREEP SOURCE_DIR
"""
import csv
import math
import os
import sys

import kctest as kc

folder = kc.setup()
source = os.path.abspath(sys.argv[2])
shared = os.path.abspath(os.path.join(source, "..", "shared"))
profiles = os.path.join(shared, "profiles")
LOAD = 70000.0


def table(shifts, yaw, name):
    """kcreep's rows of the shared placement, by shift."""
    text = (f"&wheel_rail wheel_file = '{profiles}/MBench_S1002_v3.prw', rail_file = '{profiles}/MBench_UIC60_v3.prr',\n"
            f"  shifts = {' '.join(str(s) for s in shifts)}, yaw = {yaw}, vertical_force = {LOAD} /\n"
            "&material g = 82000, nu = 0.28 /\n&solver target_error = 1e-2 /\n")
    code, out, err, _ = kc.run(text, folder, name, expect_ok=False)
    kc.check(code == 0, f"{name} runs" + ("" if code == 0 else ": " + err.strip()))
    rows = kc.read_table(os.path.join(folder, name + ".wr")) if code == 0 else []
    by_shift = {}
    for r in rows:
        by_shift.setdefault(round(r["shift"], 3), []).append(r)
    return by_shift


def compare(label, mine, theirs):
    """One shift: kcreep's patches against CONTACT's (both ordered from the field side)."""
    kc.check(len(mine) == len(theirs), f"{label}: {len(mine)} patches, CONTACT {len(theirs)}")
    for k, c in zip(mine, theirs):
        flange = k["kind"] == "flange"
        # angle and point: the tolerances of issue 46. Measured on the 0.1 mm sweep from -6 to 10 mm (every
        # shift one patch in both): tread within 0.0019 rad, 0.10 mm, 0.024 mm of radius (the largest at
        # 5.2-5.6 mm, on the gauge corner, where CONTACT's creep force carries 2 % of the load and kcreep's
        # frictionless patch needs 3 % more approach for it: the point moves 0.3 mm per 5 %); flange within
        # 0.023 rad, 0.19 mm, 0.31 mm of radius (6.7 mm: the flange root, r changes by tan(delta) = 1.6 mm
        # per mm of the point); everywhere else within 0.0004 rad, 0.02 mm, 0.005 mm
        kc.small(k["delta"] + c["delta"], 1, 0.03 if flange else 0.005,
                 f"{label} {k['kind']}: delta {k['delta']:.4f}, CONTACT {-c['delta']:.4f}")
        kc.small(k["y_rail"] - c["y_rail"], 1, 1.0 if flange else 0.3,
                 f"{label} {k['kind']}: y_rail {k['y_rail']:.3f}, CONTACT {c['y_rail']:.3f}")
        kc.small(k["r_wheel"] - c["r_wheel"], 1, 0.5 if flange else 0.03,
                 f"{label} {k['kind']}: r_wheel {k['r_wheel']:.4f}, CONTACT {c['r_wheel']:.4f}")
        share = k["fn"] * math.cos(k["delta"])
        theirs_share = c["fn"] * math.cos(c["delta"]) + c["fs"] * math.sin(c["delta"])
        kc.small(share - theirs_share, LOAD, 0.03 if flange else 0.01,
                 f"{label} {k['kind']}: fn cos(delta) {share:.0f} N, CONTACT's FN cos + FS sin {theirs_share:.0f} N")


def contact_rows(path, shift, radius, delta, y_rail, fn, fs, comment=False):
    rows = {}
    with open(path) as f:
        lines = [line for line in f if not (comment and line.startswith("#"))]
    for r in csv.DictReader(lines):
        rows.setdefault((round(float(r[shift]), 3), float(r.get("yaw_rad", 0))), []).append(
            {"delta": float(r[delta]), "y_rail": float(r[y_rail]), "fn": float(r[fn]), "fs": float(r[fs]),
             "r_wheel": radius(r)})
    return rows


if not os.path.isdir(profiles):
    kc.check(False, f"../shared/profiles missing ({profiles})")
    kc.finish()

# 1. the shared nine shifts and two yawed rows
base = contact_rows(os.path.join(shared, "contact-wr", "s1002_uic60_base.csv"), "shift_mm",
                    lambda r: 460 * (2 + float(r["cksi"])) / (2 - float(r["cksi"])), "delta_rad", "ycp_rail_mm",
                    "FN_N", "FS_N")
for yaw in (0.0, 0.005):
    shifts = sorted(s for s, y in base if y == yaw)
    mine = table(shifts, yaw, f"base_yaw{yaw}")
    for s in shifts:
        compare(f"shift {s} yaw {yaw}", mine.get(s, []), base[(s, yaw)])

# 2. continuity over three ranges, every 0.1 mm
steps = contact_rows(os.path.join(source, "tests", "data", "contact_s1002_uic60_steps.csv"), "shift_mm",
                     lambda r: float(r["r_wheel_mm"]), "delta_rad", "ycp_rail_mm", "FN_N", "FS_N", comment=True)
for lo, hi in ((0.0, 0.5), (4.8, 5.3), (6.5, 7.0)):
    shifts = [round(lo + 0.1 * k, 1) for k in range(int(round((hi - lo) / 0.1)) + 1)]
    mine = table(shifts, 0.0, f"steps_{lo}")
    for s in shifts:
        compare(f"shift {s}", mine.get(s, []), steps[(s, 0.0)])
    ours = [mine[s][0]["delta"] for s in shifts if len(mine.get(s, [])) == 1]
    theirs = [-steps[(s, 0.0)][0]["delta"] for s in shifts]
    if len(ours) == len(theirs):
        largest = max(abs(b - a) for a, b in zip(theirs, theirs[1:]))
        worst = max(abs(b - a) for a, b in zip(ours, ours[1:]))
        kc.check(worst <= 2 * largest, f"{lo}-{hi} mm: largest step of delta {worst:.4f} rad, at most twice "
                 f"CONTACT's {largest:.4f}")
kc.finish()
