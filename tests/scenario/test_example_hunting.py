"""examples/wheelset_hunting.py --check: a wheelset on S1002/UIC60 from a
kcreep.ContactTable prints its kinematic wavelength within 3 % of Klingel's
(with the table's own equivalent conicity), three critical speeds, and draws
its figure (issue 48). Measured: 9.05 m against 9.02 m (0.3 %), critical
speeds 271 km/h each (4 bisection steps, +-12 km/h), 23 s user on one thread
with the fast model on force grids of at most 350 cells.

usage: /usr/bin/python3 test_example_hunting.py KCREEP SOURCE_DIR   (numpy, scipy, matplotlib)
"""
import os
import re
import subprocess
import sys
import time

import kctest as kc

folder = kc.setup()
source_dir = os.path.abspath(sys.argv[2])
png = os.path.join(folder, "hunting.png")
t0 = time.time()
proc = subprocess.run([sys.executable, os.path.join(source_dir, "examples", "wheelset_hunting.py"), "--check",
                       "--png", png], capture_output=True, text=True, cwd=folder)
seconds = time.time() - t0
print(proc.stdout)
kc.check(proc.returncode == 0, f"--check runs ({proc.returncode}: {proc.stderr.strip()[-300:]})")
m = re.search(r"kinematic wavelength at amplitude ([\d.]+) mm: ([\d.]+) m \(Klingel: ([\d.]+) m\)", proc.stdout)
kc.check(m is not None, "the wavelength line printed")
kc.check("fast model: fast_forces on at most 350 cells a row" in proc.stdout,
         "--check runs the fast model (on force grids of at most 350 cells), not a stand-in")
if m:
    length, klingel = float(m.group(2)), float(m.group(3))
    kc.check(abs(length / klingel - 1) <= 0.03, f"wavelength {length} m within 3 % of Klingel's {klingel} m")
m = re.search(r"critical speed: (\d+) km/h \(fast model[^)]*\), (\d+) km/h \(FASTSIM\), (\d+) km/h \(linear Kalker\)",
              proc.stdout)
kc.check(m is not None, "three critical speeds printed (numbers, inside the bisection's range)")
if m:
    speeds = [float(v) for v in m.groups()]
    kc.check(all(36 < v < 432 for v in speeds), f"critical speeds {speeds} km/h inside 36-432 km/h")
kc.check(os.path.getsize(png) > 10000 if os.path.exists(png) else False, "the figure written")
print(f"wall {seconds:.1f} s")
kc.finish()
