"""The normal contact problem through the program (&patch shape = 'gap', &normal).

1. Hertz: the patch found from principal radii and a force has Hertz's
   semi-axes to O(cell) and its creep coefficients agree with those of the
   'ellipse' shape with Hertz's semi-axes on the same grid (tolerances from
   the differences measured at 40 cells across, see docs/normal.md).
2. CONTACT's kidney sample read from its .inp (contact_inp): 708 cells, FN
   and PMAX to CONTACT's printed digits; the same gap as a gap file gives the
   same row.
3. The contact mask file written on request is a valid mask: shape = 'mask'
   on it gives the same coefficients.
4. Dissimilar bodies (e1, nu1, e2, nu2): Hertz with the exact 1/E*, CONTACT's
   combined G and nu; a contact area reaching the grid's edge warns; no
   convergence within normal_max_iterations exits 3; --estimate-memory works.
5. Bad input: one line naming file, variable and value, a non-zero exit,
   nothing written (table, pressure or mask file)."""
import math
import os
import sys

import kctest as kc
from kcreep import contact_inp  # (kctest puts python/ on the path)


def agm_k_e(k):
    """K(e) and E(e) for the axis ratio k = sqrt(1 - e^2) (arithmetic-geometric mean)."""
    a, b, e2 = 1.0, k, 1 - k * k
    s, w, c = e2 / 2, 1.0, None
    for _ in range(60):
        a1 = (a + b) / 2
        c = e2 / (4 * a1) if c is None else c * c / (4 * a1)
        b = math.sqrt(a * b)
        a = a1
        s += w * c * c
        w *= 2
        if c < 1e-17 * a:
            break
    kk = math.pi / (2 * a)
    return kk, kk * (1 - s)


def hertz(rx, ry, compliance, force):
    """Semi-axes (along x, y), p0 and approach of Hertz's contact (Johnson sec. 4.2)."""
    A, B = 1 / (2 * rx), 1 / (2 * ry)
    amin, bmax = min(A, B), max(A, B)
    lo, hi = 1e-9, 1.0
    for _ in range(200):   # k from B/A = (E/k^2 - K)/(K - E)
        k = (lo + hi) / 2
        kk, ee = agm_k_e(k)
        ratio = (ee / k**2 - kk) / (kk - ee) if k < 1 - 1e-12 else 1.0
        if ratio > bmax / amin:
            lo = k
        else:
            hi = k
    kk, ee = agm_k_e(k)
    e2 = 1 - k * k
    ke = (kk - ee) / e2 if e2 > 1e-12 else math.pi / 4
    major = (3 * force * compliance * ke / (2 * math.pi * amin)) ** (1 / 3)
    minor = k * major
    p0 = 3 * force / (2 * math.pi * major * minor)
    delta = compliance * p0 * minor * kk
    a, b = (major, minor) if A <= B else (minor, major)
    return a, b, p0, delta


folder = kc.setup()
samples = os.path.abspath(sys.argv[2]) if len(sys.argv) > 2 else None

# 1. Hertz: patch, semi-axes and coefficients against the ellipse shape
G, NU, F, N = 1.0, 0.25, 1.0, 40
for rx, ry in [(1, 1), (3, 1), (1, 3)]:
    a, b, p0, delta = hertz(rx, ry, (1 - NU) / G, F)
    dx, dy = 2 * a / N, 2 * b / N
    mx = my = N + 10
    x0, y0 = -(mx - 1) * dx / 2, -(my - 1) * dy / 2
    gap = kc.coefficients(f"&patch shape='gap', mx={mx}, my={my}, dx={dx!r}, dy={dy!r}, x0={x0!r}, y0={y0!r} /\n"
                          f"&material g={G}, nu={NU} /\n&normal rx={rx}, ry={ry}, normal_force={F} /\n",
                          folder, f"gap_{rx}_{ry}")
    ell = kc.coefficients(f"&patch shape='ellipse', semi_a={a!r}, semi_b={b!r}, mx={N}, my={N} /\n"
                          f"&material g={G}, nu={NU} /\n", folder, f"ell_{rx}_{ry}")
    label = f"Rx/Ry = {rx / ry:g}, {N} cells across"
    kc.check(abs(gap["fn"] / F - 1) < 1e-12, f"{label}: fn as prescribed ({gap['fn']:.15g})")
    # measured: approach 1.4e-4 on this grid (an even grid; docs/normal.md has the convergence table)
    kc.check(abs(gap["approach"] / delta - 1) < 2e-4, f"{label}: approach vs Hertz ({gap['approach'] / delta - 1:.2e})")
    # (an even grid: the largest cell pressure sits half a cell off the centre; measured 5.6e-4)
    kc.check(abs(gap["pmax"] / p0 - 1) < 8e-4, f"{label}: pmax vs Hertz ({gap['pmax'] / p0 - 1:.2e})")
    # measured: area within 1.4 % of pi a b at 40 cells across (the area is first order in the cell size)
    kc.check(abs(gap["n"] * dx * dy / (math.pi * a * b) - 1) < 0.02,
             f"{label}: area vs pi a b ({gap['n'] * dx * dy / (math.pi * a * b) - 1:.2e})")
    for c in ("c11", "c22", "c23"):
        diff = gap[c] / ell[c] - 1
        # measured: at most 1.13 % (c23, Rx/Ry = 3) at 40 cells across: the boundary cells of
        # the two patches differ (contact cells vs centres inside the ellipse), an O(cell) effect
        kc.check(abs(diff) < 0.015, f"{label}: {c} of the patch found vs the ellipse shape ({diff:.2e})")

# 2. CONTACT's kidney sample
if samples and os.path.isdir(samples):
    inp = os.path.join(samples, "kidney_nu25.inp")
    r = kc.coefficients(f"&patch shape='gap' /\n&normal contact_inp='{inp}' /\n"
                        f"&output contact_mask_file='kidney.mask', pressure_file='kidney.p' /\n", folder, "kidney")
    kc.check(int(r["n"]) == 708, f"kidney from its .inp: {int(r['n'])} contact cells (CONTACT: 708)")
    kc.check(f"{r['fn']:.3E}" == "1.964E+04", f"kidney: FN {r['fn']:.6e} prints as CONTACT's 1.964E+04")
    kc.check(f"{r['pmax']:.3E}" == "2.364E+04", f"kidney: PMAX {r['pmax']:.6e} prints as CONTACT's 2.364E+04")
    kc.check(r["normal_residual"] <= 1e-10, f"kidney: complementarity residual {r['normal_residual']:.1e} <= 1e-10")
    # 3. the contact mask is a mask file; the same patch gives the same coefficients
    # (target_error = 0: the mask solved on its own grid, as the gap patch is)
    m = kc.coefficients(f"&patch shape='mask', mask_file='kidney.mask' /\n&material g=82000, nu=0.25 /\n"
                        f"&solver target_error=0 /\n",
                        folder, "kidney_mask")
    kc.check(int(m["n"]) == 708 and all(abs(m[c] / r[c] - 1) < 1e-12 for c in ("f11", "f22", "f23")),
             "contact_mask_file read back as shape = 'mask': same cells, same coefficients")
    with open(os.path.join(folder, "kidney.p")) as f:
        p = [float(line.split()[4]) for line in f if not line.startswith("#")]
    dxy = (1 / 24) ** 2
    kc.check(len(p) == 708 and abs(sum(p) * dxy / r["fn"] - 1) < 1e-12 and abs(max(p) / r["pmax"] - 1) < 1e-15,
             "pressure_file: one pressure per contact cell, summing to fn, maximum pmax")
    # the same gap as a gap file (written from the .inp values) gives the same row
    values = contact_inp.gap_values(inp, 36 * 60)
    rows = [" ".join(values[j * 36:(j + 1) * 36]) for j in range(60)]
    header = f"36 60 {1 / 24!r} {1 / 24!r} {-0.625 + 1 / 48!r} {-1.25 + 1 / 48!r}"
    # (target_error = 0: the gap file's own grid, as the .inp case is solved)
    gf = kc.run("&patch shape='gap' /\n&material g=82000, nu=0.25 /\n&normal gap_file='kidney.gap', approach=0.2 /\n"
                "&solver target_error=0 /\n",
                folder, "kidney_gapfile", files={"kidney.gap": header + "\n" + "\n".join(rows) + "\n"})[3][0]
    kc.check(int(gf["n"]) == 708 and abs(gf["fn"] / r["fn"] - 1) < 1e-12,
             "the kidney gap as a gap file: same contact area and force")
else:
    kc.check(False, "CONTACT samples folder given as argument 2")

# dissimilar bodies (E, nu per body): the exact 1/E* in the normal problem, CONTACT's combined
# G, nu in the tangential one; sphere of relative radius 1 at approach 1e-3, automatic grid
E1, N1, E2, N2, D = 210000.0, 0.3, 70000.0, 0.33, 1e-3
r = kc.coefficients(f"&patch shape='gap' /\n&normal rx=1, ry=1, approach={D}, e1={E1}, nu1={N1}, e2={E2}, nu2={N2} /\n",
                    folder, "dissimilar")
c = (1 - N1**2) / E1 + (1 - N2**2) / E2
f_hertz, p_hertz = 4 / (3 * c) * D**1.5, 2 / (math.pi * c) * math.sqrt(D)
g1, g2 = E1 / (2 * (1 + N1)), E2 / (2 * (1 + N2))
g = 2 / (1 / g1 + 1 / g2)
nu = g * (N1 / g1 + N2 / g2) / 2
kc.check(abs(r["g"] / g - 1) < 1e-14 and abs(r["nu"] / nu - 1) < 1e-14, f"dissimilar bodies: combined G = {r['g']:.6g}, nu = {r['nu']:.6g}")
# measured on the default automatic grid (60 cells across, contact ~30): force +3.6e-4, pmax -8.4e-4
kc.check(abs(r["fn"] / f_hertz - 1) < 1e-3 and abs(r["pmax"] / p_hertz - 1) < 1.5e-3,
         f"dissimilar bodies: fn {r['fn'] / f_hertz - 1:+.1e}, pmax {r['pmax'] / p_hertz - 1:+.1e} against Hertz with the exact 1/E*")

# the fine normal grid of error control stops at residual 1e-8 unless the caller set one
# (kcreep_refine_constants gap_normal_tolerance); a given normal_tolerance holds there too
sphere = "&patch shape='gap' /\n&normal rx=1, ry=2, approach=0.01{} /\n"
r_default = kc.coefficients(sphere.format(""), folder, "tol_default")
r_given = kc.coefficients(sphere.format(", normal_tolerance=1e-11"), folder, "tol_given")
kc.check(1e-11 < r_default["normal_residual"] <= 1e-8 and r_given["normal_residual"] <= 1e-11,
         f"fine normal grid: residual {r_default['normal_residual']:.1e} (default, <= 1e-8), "
         f"{r_given['normal_residual']:.1e} (normal_tolerance = 1e-11)")
kc.check(all(abs(r_default[c] / r_given[c] - 1) < 1e-6 for c in ("f11", "f22", "f23")),
         "fine normal grid at 1e-8: the coefficients of 1e-11 to six digits")

# a contact area that reaches the grid's edge: solved, with a warning
code, out, err, table = kc.run("&patch shape='gap' /\n&normal gap_file='flat.gap', approach=0.1 /\n", folder, "edge",
                               expect_ok=False, files={"flat.gap": "12 10 1 1 0 0\n" + "0 " * 12 + "\n" + ("0 " * 12 + "\n") * 9})
kc.check(code == 0 and "reaches the edge of the gap's grid" in err, "contact up to the grid's edge: exit 0 and a warning")

# no convergence within normal_max_iterations: exit 3, one line
code, out, err, table = kc.run("&patch shape='gap' /\n&normal rx=1, ry=1, approach=0.01, normal_max_iterations=2 /\n",
                               folder, "noconv", expect_ok=False)
kc.check(code == 3 and len(err.strip().split("\n")) == 1 and "no convergence in 2 iterations" in err,
         f"normal_max_iterations = 2: exit {code}, {err.strip()!r}")

# --estimate-memory on a gap case: a positive byte count (normal solve + tangential bound)
import subprocess
with open(os.path.join(folder, "est.nml"), "w") as f:
    f.write("&patch shape='gap' /\n&normal rx=1, ry=2, approach=0.01 /\n")
proc = subprocess.run([kc.KCREEP, "--estimate-memory", "est.nml"], cwd=folder, capture_output=True, text=True)
# one line 'FILE BYTES PATH'
kc.check(proc.returncode == 0 and int(proc.stdout.split()[-2]) > 0,
         f"--estimate-memory of a gap case: exit {proc.returncode}, {proc.stdout.strip()} bytes")
# ... under error control it solves the normal problems as the run does and counts
# the ladder's finest level at the limit the run holds it to (region_max_level
# across the contact area, kcreep_solve_memory region_patch_bytes): at least the
# run's peak RSS, and well below the whole cell budget it counted before (>200 MB;
# measured 90.7 MB against a 33.5 MB peak, one thread); a wheel/rail table likewise
# (shift 0: 89.9 MB against 46.7 MB)
def peak_rss(name):
    out = subprocess.run([sys.executable, "-c", "import resource, subprocess, sys; "
                          "subprocess.run(sys.argv[1:], capture_output=True, check=True); "
                          "print(resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss * 1024)",
                          kc.KCREEP, name], cwd=folder, capture_output=True, text=True)
    return int(out.stdout.strip() or 0)


rows = [ln for ln in proc.stdout.splitlines() if ln.strip()]
rss = peak_rss("est.nml")
kc.check(0 < rss <= int(rows[0].split()[-2]) < 2e8 and rows[0].split()[-1] == "iterative",
         f"--estimate-memory of a gap under error control: {rows[0]}, peak {rss} B")
shared = os.path.join(kc.REPO, "..", "shared", "profiles")
if os.path.isdir(shared):
    with open(os.path.join(folder, "wr.nml"), "w") as f:
        f.write(f"&wheel_rail wheel_file = '{shared}/MBench_S1002_v3.prw', rail_file = '{shared}/MBench_UIC60_v3.prr', "
                "shifts = 0, vertical_force = 80000 /\n&material g = 82000, nu = 0.28 /\n")
    proc = subprocess.run([kc.KCREEP, "--estimate-memory", "wr.nml"], cwd=folder, capture_output=True, text=True)
    rss = peak_rss("wr.nml")
    kc.check(proc.returncode == 0 and 0 < rss <= int(proc.stdout.split()[-2]) < 2e8
             and proc.stdout.split()[-1] == "iterative",
             f"--estimate-memory of a wheel/rail table: {proc.stdout.strip()}, peak {rss} B")

# 5. bad input
GOOD = "&patch shape='gap' /\n&material g=1, nu=0.25 /\n"
OUT = "&output pressure_file='bad.p', contact_mask_file='bad.mask' /\n"
bad_cases = [
    ("no interpenetration", GOOD + "&normal rx=1, ry=1, approach=-0.01 /\n" + OUT, {}, "do not interpenetrate"),
    ("gap file all above the approach", GOOD + "&normal gap_file='g.gap', approach=0.5 /\n" + OUT,
     {"g.gap": "2 2 1 1 0 0\n1 1\n1 1\n"}, "do not interpenetrate"),
    ("zero force", GOOD + "&normal rx=1, ry=1, normal_force=0 /\n" + OUT, {}, "normal_force = 0"),
    ("negative force", GOOD + "&normal rx=1, ry=1, normal_force=-5 /\n" + OUT, {}, "normal_force = -5"),
    ("gap file: a row too short", GOOD + "&normal gap_file='g.gap', approach=0.5 /\n" + OUT,
     {"g.gap": "3 2 1 1 0 0\n0 0 0\n0 0\n"}, "has 2 values, the header says mx = 3"),
    ("gap file: rows missing", GOOD + "&normal gap_file='g.gap', approach=0.5 /\n" + OUT,
     {"g.gap": "2 3 1 1 0 0\n0 0\n0 0\n"}, "the header says my = 3"),
    ("gap file: NaN", GOOD + "&normal gap_file='g.gap', approach=0.5 /\n" + OUT,
     {"g.gap": "2 2 1 1 0 0\n0 nan\n0 0\n"}, "finite numbers only"),
    ("both approach and force", GOOD + "&normal rx=1, ry=1, approach=0.1, normal_force=1 /\n" + OUT, {},
     "exactly one of approach and normal_force"),
    ("no gap source", GOOD + "&normal approach=0.1 /\n" + OUT, {}, "exactly one undeformed distance"),
    ("&normal without shape gap", "&patch shape='ellipse' /\n&normal rx=1, ry=1, approach=0.1 /\n", {},
     "&normal is only read with &patch shape = 'gap'"),
]
for label, text, files, phrase in bad_cases:
    name = "bad_" + "".join(ch if ch.isalnum() else "_" for ch in label)
    for stale in ("bad.p", "bad.mask", name + ".tab"):
        if os.path.exists(os.path.join(folder, stale)):
            os.remove(os.path.join(folder, stale))
    code, out, err, _ = kc.run(text, folder, name, expect_ok=False, files=files)
    lines = err.strip().split("\n")
    kc.check(code == 2, f"{label}: exit 2 (got {code})")
    # the line names the file at fault: the namelist, or the gap file it points to
    source = "gap_file 'g.gap'" if "gap file:" in label else name + ".nml"
    kc.check(len(lines) == 1 and phrase in lines[0] and source in lines[0],
             f"{label}: one line naming the file and the value: {lines[0]!r}")
    kc.check(not any(os.path.exists(os.path.join(folder, f)) for f in ("bad.p", "bad.mask", name + ".tab")),
             f"{label}: nothing written")

kc.finish()
