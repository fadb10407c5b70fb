"""The wheel-rail contact table from a call: the C API (tests/api/wheel_rail_api.c:
kcreep_set_profiles, kcreep_set_track, kcreep_wheel_rail, kcreep_get_wheel_rail
and their errors) and Python (kcreep.wheel_rail, Solver.wheel_rail) give the
program's &wheel_rail table: the same columns, the same numbers. Likewise the
wheelset table (kcreep_wheelset, kcreep_get_wheelset, kcreep_set_left_profiles;
kcreep.wheelset) and the program's wheelset = .true. (.ws).

usage: /usr/bin/python3 test_wheel_rail_api.py KCREEP SOURCE_DIR C_PROGRAM   (needs numpy)
"""
import math
import os
import subprocess
import sys

import kctest as kc

folder = kc.setup()
source_dir = os.path.abspath(sys.argv[2])
program = os.path.abspath(sys.argv[3])
sys.path.insert(0, os.path.join(source_dir, "python"))
import numpy as np  # noqa: E402
import kcreep  # noqa: E402


circle = kc.circle_profile


# a crowned wheel (profile radius 300 mm) on a 300 mm rail crown, as tests/scenario/test_wheel_rail.py
for name, text in {"wheel.dat": circle(300, 40, True), "rail.dat": circle(300, 35, False)}.items():
    with open(os.path.join(folder, name), "w") as f:
        f.write(text)
wheel, rail = os.path.join(folder, "wheel.dat"), os.path.join(folder, "rail.dat")
G, NU, FORCE, FBPOS, SHIFTS = 82000.0, 0.28, 80000.0, -72.5, [-4.0, 6.0]

# the program
code, out, err, _ = kc.run(
    f"&wheel_rail wheel_file = 'wheel.dat', rail_file = 'rail.dat', flange_back_position = {FBPOS},\n"
    f"  shifts = {' '.join(map(str, SHIFTS))}, vertical_force = {FORCE}, wheelset = .true. /\n"
    f"&material g = {G}, nu = {NU} /\n",
    folder, "cli", expect_ok=False)
kc.check(code == 0, "the program's table" + ("" if code == 0 else ": " + err.strip()))
cli = kc.read_table(os.path.join(folder, "cli.wr")) if code == 0 else []
header = [l for l in open(os.path.join(folder, "cli.wr"))if l.startswith("#")][-1][1:].split() if code == 0 else []

# C
c_out = os.path.join(folder, "c.wr")
proc = subprocess.run([program, wheel, rail, c_out, str(G), str(NU), str(FORCE), str(FBPOS)] + list(map(str, SHIFTS)),
                      capture_output=True, text=True)
kc.check(proc.returncode == 0, f"C API checks and table: {proc.stdout.strip()} {proc.stderr.strip()}")
c_rows = kc.read_table(c_out) if proc.returncode == 0 else []

# Python
py = kcreep.wheel_rail(wheel, rail, SHIFTS, g=G, nu=NU, vertical_force=FORCE, flange_back_position=FBPOS)
kc.check(list(py) == kcreep.WHEEL_RAIL_COLUMNS == header, f"Python's columns are the program's ({list(py)})")
kc.check(c_rows and list(c_rows[0]) == header, "C's columns (KCREEP_WHEEL_RAIL_COLUMN_NAMES) are the program's")
kc.check(len(cli) == len(c_rows) == len(py["shift"]) == 2, f"2 rows each ({len(cli)}, {len(c_rows)}, {len(py['shift'])})")
kc.check(all(isinstance(v, np.ndarray) for v in py.values()), "Python gives numpy arrays")
flags = {"ok": 0}
for r, (row, crow) in enumerate(zip(cli, c_rows)):
    for name in header:
        if name == "verdict":
            kc.check((crow[name] == 0) == (row[name] == "ok") and py[name][r] == crow[name],
                     f"row {r}: verdict bits {crow[name]} for '{row[name]}'")
            continue
        if name == "kind":
            kc.check((crow[name] == 1) == (row[name] == "flange") and py[name][r] == row[name],
                     f"row {r}: kind {crow[name]} (C), {py[name][r]} (Python) for '{row[name]}'")
            continue
        # C and Python run the same library: the same numbers to the last digit; the program
        # prints 7 to 9 digits (es14.6 the fewest: 1e-6 relative), the estimates 2 (es10.2)
        kc.check(py[name][r] == crow[name], f"row {r}: {name} Python {py[name][r]!r} == C {crow[name]!r}")
        tol = 6e-3 if name.startswith("err") else 1e-4 if name == "turn" else 1e-6   # turn: es12.4
        scale = max(abs(row[name]), 1e-300)
        kc.check(abs(crow[name] - row[name]) <= tol * scale + (1e-12 if name == "yaw" else 0),
                 f"row {r}: {name} C {crow[name]:.9g} = program {row[name]:.9g} (printed digits)")

# the wheelset: program, C, Python
cli_ws = kc.read_table(os.path.join(folder, "cli.ws")) if code == 0 else []
c_ws = kc.read_table(c_out + ".ws") if proc.returncode == 0 else []
py_ws = kcreep.wheelset(wheel, rail, SHIFTS, g=G, nu=NU, vertical_force=FORCE, flange_back_position=FBPOS)
ws_header = [l for l in open(os.path.join(folder, "cli.ws")) if l.startswith("#")][-1][1:].split() if code == 0 else []
kc.check(list(py_ws) == kcreep.WHEELSET_COLUMNS == ws_header and c_ws and list(c_ws[0]) == ws_header,
         f"the wheelset columns of Python, C and the program agree ({ws_header})")
kc.check(len(cli_ws) == len(c_ws) == len(py_ws["shift"]) == 2, "2 wheelset rows each")
for r, (row, crow) in enumerate(zip(cli_ws, c_ws)):
    for name in ws_header:
        kc.check(py_ws[name][r] == crow[name], f"wheelset row {r}: {name} Python {py_ws[name][r]!r} == C")
        # the program prints 9 digits (es16.8) at least: 1e-7 relative, and roll 0 at no shift
        kc.check(abs(crow[name] - row[name]) <= 1e-7 * abs(row[name]) + 1e-15,
                 f"wheelset row {r}: {name} C {crow[name]:.10g} = program {row[name]:.10g}")
try:
    kcreep.wheelset(wheel, rail, [0.0], g=G, nu=NU, vertical_force=FORCE, left_wheel_file="no-such-left.dat")
    kc.check(False, "a missing left_wheel_file refused")
except kcreep.KcreepError as e:
    kc.check(e.code == 2 and "no-such-left.dat" in str(e), f"a missing left_wheel_file refused: {e}")

# errors become KcreepError with the library's message
for kwargs, words in (({"side": "middle", "vertical_force": FORCE}, "side"),
                      ({"vertical_force": FORCE, "approach": 0.1}, "exactly one"),
                      ({"vertical_force": FORCE, "flange_back_position": -400}, "never meets")):
    try:
        kcreep.wheel_rail(wheel, rail, [0.0], g=G, nu=NU, flange_back_position=kwargs.pop("flange_back_position", FBPOS),
                          **kwargs)
        kc.check(False, f"{kwargs} refused")
    except kcreep.KcreepError as e:
        kc.check(e.code == 2 and words in str(e), f"{kwargs} refused: {e}")
kc.finish()
