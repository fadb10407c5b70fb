#!/usr/bin/env python3
"""kcreep's &wheel_rail table against CONTACT's module 1 on S1002 / UIC60 (the
placement of ../shared/contact-wr: right wheel, 70 kN, yaw 0; DX = DS = 0.2,
A_SEP 90 deg, D_SEP 8, D_COMB 4, mu 0.3, V 2000 mm/s, the wheel's angular
velocity for the nominal radius 460 mm).

  lab/contact_wr_compare.py input SHIFT ... > CASE.inp
      writes CONTACT's input for those shifts (mm); run it beside the two
      profiles (../shared/profiles) as  contact_linux64 2 CASE
  lab/contact_wr_compare.py table CASE.out > CASE.csv
      CONTACT's output as one row per shift and patch: shift, patch count,
      FN, FS, the reference point on the rail, delta (CONTACT's sign), its
      rolling radius r = 460 (2 + CKSI) / (2 - CKSI) (CKSI refers to the mean
      of the two velocities) and its warnings
  lab/contact_wr_compare.py compare TABLE.wr CASE.out
      kcreep's rows beside CONTACT's: patch counts, delta, y_rail, r_wheel,
      the vertical share (kcreep fn cos(delta), CONTACT FN cos + FS sin) and
      the largest differences by kind

docs/wheel_rail.md, "Against CONTACT": the table of
scripts/figures/s1002_uic60_contact.nml against CONTACT at every 0.1 mm.
Standard library only.
"""
import math
import os
import re
import sys

if any(a in ("-h", "--help") for a in sys.argv[1:]) or len(sys.argv) < 3:
    print(__doc__.strip())
    sys.exit(0 if len(sys.argv) >= 2 else 2)

LOAD, R0, V = 70000.0, 460.0, 2000.0


def deck(shifts):
    """CONTACT's input: the first case in full, then the wheelset position of each further one."""
    vpitch = -V / R0
    first = f""" 1203100    C-P-B-T-N-F-S
 0022033    V-L-D-C-M-Z-E
 0000321    H-G-I-A-O-W-R
    999     100    30    1     1e-5         MAXGS , MAXIN , MAXNR , MAXOUT, EPS
  0.300   0.300                                 FSTAT, FKIN
  0.280   0.280   82000.  82000.                POISS 1,2,  GG 1,2
  0.200   0.200   1.000   90d   8.0   4.0      DX, DS, DQREL, A_SEP, D_SEP, D_COMB
   14.0     0    1435.0   0.000                GAUGHT, GAUGSQ, GAUGWD, CANT
  'MBench_UIC60_v3.prr'   0     1.0   0.0       RFNAME, MIRRORY, SCALE, SMOOTH
     0.0    0.0   0.000   0.0   0.0   0.000     DY, DZ, ROLL, VY, VZ, VROLL
  1360.0  -70.0   460.0                         FBDIST, FBPOS, NOMRAD
  'MBench_S1002_v3.prw'   0     1.0   0.0       WFNAME, MIRRORY, SCALE, SMOOTH
"""
    later = """ 1203100    C-P-B-T-N-F-S
 0111002    V-L-D-C-M-Z-E
 0100321    H-G-I-A-O-W-R
"""
    text = ""
    for k, y in enumerate(shifts):
        text += "  1 MODULE\n" + (first if k == 0 else later)
        text += f"  0.0  {y:.4f}  {LOAD}  0.0 0.0  0.0      S, Y, FZ, ROLL, YAW, PITCH\n"
        text += f" {V}  0.0  0.0  0.0  0.0  {vpitch:.10f}  VS,VY,VZ, VROLL,VYAW,VPITCH\n"
    return text + "  0 MODULE\n"


def contact_rows(path):
    """One dict per case and patch of CONTACT's .out."""
    rows, case, lines = [], None, open(path).read().splitlines()
    for i, line in enumerate(lines):
        following = lines[i + 1].split() if i + 1 < len(lines) else []
        if re.match(r"^ Case\s+\d+", line):
            case = {"warnings": 0}
        elif "WARNING" in line and case is not None:
            case["warnings"] += 1
        elif "WHEEL-RAIL CONTACT" in line:
            m = re.search(r"(\d+) CONTACT PATCH", line)
            case["npatch"] = int(m.group(1)) if m else 0
        elif "S_WS        Y_WS" in line:
            case["shift"] = float(following[1])
        elif "DATA FOR CONTACT PATCH" in line:
            rows.append(dict(case))
        elif "XCP(TR)     YCP(TR)" in line:
            rows[-1].update(delta=float(following[3]), y_rail=float(following[4]))
        elif line.strip().startswith("CHI") and "CKSI" in line:
            c = float(following[3])
            rows[-1]["r_wheel"] = R0 * (2 + c) / (2 - c)
        elif line.strip().startswith("FN ") and "FS" in line:
            rows[-1].update(fn=float(following[0]), fs=float(following[2]))
    return rows


def kcreep_rows(path):
    here = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    sys.path.insert(0, os.path.join(here, "python"))
    from kcreep import table  # python/kcreep/table.py, standard library only
    return table.read(path)


mode = sys.argv[1]
if mode == "input":
    sys.stdout.write(deck([float(s) for s in sys.argv[2:]]))
elif mode == "table":
    print("shift_mm,npatch,FN_N,FS_N,ycp_rail_mm,delta_rad,r_wheel_mm,warnings")
    for r in contact_rows(sys.argv[2]):
        print(f"{r['shift']:.4g},{r['npatch']},{r['fn']:.6g},{r['fs']:.6g},{r['y_rail']:.4f},{r['delta']:.4f},"
              f"{r['r_wheel']:.4f},{r['warnings']}")
elif mode == "compare" and len(sys.argv) == 4:
    ours, theirs = {}, {}
    for r in kcreep_rows(sys.argv[2]):
        ours.setdefault(round(r["shift"], 3), []).append(r)
    for r in contact_rows(sys.argv[3]):
        theirs.setdefault(round(r["shift"], 3), []).append(r)
    worst = {}
    print("shift  n_k n_c  kind    delta_k  delta_c   y_rail_k y_rail_c  r_wheel_k  r_wheel_c  share_k share_c")
    for s in sorted(theirs):
        k_rows, c_rows = ours.get(s, []), theirs[s]
        if len(k_rows) != len(c_rows):
            print(f"{s:5.1f} {len(k_rows):4d} {len(c_rows):3d}  patch counts differ")
        for k, c in zip(k_rows, c_rows):
            share_k = k["fn"] * math.cos(k["delta"]) / LOAD
            share_c = (c["fn"] * math.cos(c["delta"]) + c["fs"] * math.sin(c["delta"])) / LOAD
            print(f"{s:5.1f} {len(k_rows):4d} {len(c_rows):3d}  {k['kind']:6s} {k['delta']:8.4f} {-c['delta']:8.4f}  "
                  f"{k['y_rail']:8.3f} {c['y_rail']:8.3f}  {k['r_wheel']:9.3f} {c['r_wheel']:9.3f}  "
                  f"{share_k:7.4f} {share_c:7.4f}")
            w = worst.setdefault(k["kind"], [0.0, 0.0, 0.0, 0.0])
            for j, d in enumerate((k["delta"] + c["delta"], k["y_rail"] - c["y_rail"], k["r_wheel"] - c["r_wheel"],
                                   share_k - share_c)):
                w[j] = max(w[j], abs(d))
    for kind, w in sorted(worst.items()):
        print(f"# {kind}: largest differences delta {w[0]:.4f} rad, y_rail {w[1]:.3f} mm, r_wheel {w[2]:.3f} mm, "
              f"share {w[3]:.4f} of the load")
else:
    sys.exit("contact_wr_compare.py: error: see --help")
