"""docs/convergence.md cannot drift from the code.

1. docs/convergence.md is exactly what scripts/make_report.py makes of its
   template and docs/data (so every number in it comes from the data).
2. The cheap points of the data (unit circle, nu = 0.25, 10, 20 and 40
   cells per direction, both schemes) are recomputed with this kcreep and
   must match the tables the report was made from: the coefficients to
   1e-9 (the tables carry 16 digits; a change of the code shows at once),
   the Richardson order and limit of 10/20/40 to the digits printed, and
   kcreep's &solver extrapolate from 10 x 10 to the '+extrapolate' rows.
"""
import math
import os
import subprocess
import sys

import kctest as kc

repo = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(repo, "scripts"))
from richardson import read_table, observed_order, extrapolate  # noqa: E402

folder = kc.setup()
data = os.path.join(repo, "docs", "data")
proc = subprocess.run([sys.executable, os.path.join(repo, "scripts", "make_report.py"), "--check"],
                      capture_output=True, text=True)
kc.check(proc.returncode == 0, "docs/convergence.md matches its template and data: " + (proc.stdout + proc.stderr).strip())

sweep = {r["case"]: r for r in read_table(os.path.join(data, "sweep_n.dat"))}
richardson = {}
with open(os.path.join(data, "richardson_sweep_n.dat")) as f:
    for line in f:
        if not line.startswith("#") and line.strip():
            w = line.split()
            richardson[(w[0], w[1], w[2], w[3], w[4])] = w
# The header of every docs/data/richardson*.dat must say what its last column
# holds: 100 (f0/klt - 1), in percent (the values are percent, e.g. +1.1560
# for a limit 1.156 % above Kalker's).
for name in sorted(os.listdir(data)):
    if not (name.startswith("richardson") and name.endswith(".dat")):
        continue
    with open(os.path.join(data, name)) as f:
        lines = f.read().splitlines()
    comments = [l for l in lines if l.startswith("#")]
    columns = comments[-1][1:].split()
    last = columns[-1]
    described = [l for l in comments[:-1] if f"{last}:" in l]
    text = described[0].split(f"{last}:", 1)[1] if described else ""
    kc.check("percent" in text and "100" in text,
             f"{name}: the header describes column {last} as a percentage ({text.strip()!r})")
    worst = 0.0
    for l in lines:
        if l.startswith("#") or not l.strip():
            continue
        w = dict(zip(columns, l.split()))
        f0, klt, vs = float(w["f0"]), float(w["klt"]), float(w[last])
        if f0 == f0 and klt == klt:
            worst = max(worst, abs(vs - 100 * (f0 / klt - 1)))
    # the limit is printed with 6 decimals, the percentage with 4: 1e-3 covers both roundings
    kc.check(worst <= 1e-3, f"{name}: {last} = 100 (f0/klt - 1) on every row (largest difference {worst:.1e})")

fresh = {}
for scheme in ("collocation", "backward"):
    for m in (10, 20, 40):
        name = f"r1_paper_{scheme}_m{m}"
        row = kc.coefficients(kc.namelist(f"shape='ellipse', semi_a=1, semi_b=1, mx={m}, my={m}", "nu=0.25",
                                          f"{kc.scheme_setting(scheme, 0.5)}"), folder, name)
        fresh[(scheme, m)] = row
        quoted = sweep[name]
        for c in ("c11", "c22", "c23"):
            kc.close(row[c], float(quoted[c]), 1e-9, f"{name} {c} as in docs/data/sweep_n.dat")
    for c in ("c11", "c22", "c23"):
        h = [1 / math.sqrt(fresh[(scheme, m)]["mx"] * fresh[(scheme, m)]["my"]) for m in (10, 20, 40)]
        f = [fresh[(scheme, m)][c] for m in (10, 20, 40)]
        p = observed_order(h, f)
        w = richardson[(f"r1_paper_{scheme}", "10", "20", "40", c)]
        if p is None:
            kc.check(w[8] == "nan", f"{scheme} {c}: 10/20/40 has no order, as the report says")
        else:
            kc.check(abs(p - float(w[8])) <= 1e-3, f"{scheme} {c}: order of 10/20/40 {p:.4f} as quoted {w[8]}")
            kc.check(abs(extrapolate(h, f, p) - float(w[9])) <= 1e-6,
                     f"{scheme} {c}: limit of 10/20/40 {extrapolate(h, f, p):.6f} as quoted {w[9]}")

# kcreep's own &solver extrapolate from 10 x 10 must give the '+extrapolate 40' rows the report quotes
ext = {}
for scheme in ("collocation", "backward"):
    ext[scheme] = kc.coefficients(kc.namelist("shape='ellipse', semi_a=1, semi_b=1, mx=10, my=10", "nu=0.25",
                                              f"{kc.scheme_setting(scheme, 0.5)}, extrapolate=.true."),
                                  folder, f"ext_{scheme}")
evt = os.path.join(data, "error_vs_time.dat")
with open(evt) as f:
    for line in f:
        w = line.split()
        if line.startswith("#") or not w or not w[0].endswith("+extrapolate") or w[1] != "40":
            continue
        row = ext[w[0].split("+")[0]]
        for i, c in enumerate(("11", "22", "23")):
            kc.check(abs(row["ext" + c] - float(w[4 + i])) <= 1e-6,
                     f"kcreep extrapolate {w[0]} from 10 x 10: ext{c} {row['ext' + c]:.6f} as quoted {w[4 + i]}")

with open(evt) as f:
    for line in f:
        w = line.split()
        if line.startswith("#") or not w or int(w[1]) not in (10, 20, 40):
            continue
        row = fresh.get((w[0], int(w[1])))
        if row is None:
            continue
        for i, c in enumerate(("c11", "c22", "c23")):
            kc.check(abs(row[c] - float(w[4 + i])) <= 1e-6, f"error_vs_time {w[0]} {w[1]} {c} {row[c]:.6f} as quoted {w[4 + i]}")
kc.finish()
