"""What a new user runs into: one section per behaviour, chosen by the second
argument (CTest runs each section as its own test).

    test_user_defects.py PATH/TO/kcreep SECTION

paths       relative file names inside a namelist are relative to the
            namelist's folder in every mode (single, --batch, --estimate-memory)
given       a value the user wrote is used or refused, never replaced or ignored
spin        the spin centre: centroid in summary and table, &solver spin_centre,
            a warning when the origin lies outside the patch's bounding box
extrap      extrapolate checks memory for the path each level takes
newline     a namelist whose last line has no newline is read
memlimit    RLIMIT_AS counts as a memory limit; a failed allocation is the
            documented one-line error
estimate    --estimate-memory: 'FILE BYTES PATH' per line (PATH: the solve path,
            dense or iterative), an error line for a bad file, the others
            still estimated, exit status 2
lock        a second kcreep --batch on the same table is refused at once
names       batch cases named by their path relative to the list; two cases
            writing the same traction_file are refused
"""
import os
import re
import resource
import subprocess
import sys
import time

import kctest as kc

SECTION = sys.argv.pop(2) if len(sys.argv) > 2 else None
folder = kc.setup()


def write(path, text):
    os.makedirs(os.path.dirname(path) or ".", exist_ok=True)
    with open(path, "w") as f:
        f.write(text)


def run(args, cwd=folder, **kw):
    return subprocess.run([kc.KCREEP] + args, cwd=cwd, capture_output=True, text=True, **kw)


def one_error_line(proc, what, *words):
    lines = proc.stderr.strip().splitlines()
    ok = len(lines) == 1 and lines[0].startswith("kcreep: error: ") and all(w in lines[0] for w in words)
    kc.check(ok, f"{what}: one error line naming {words} ({proc.stderr.strip()[:300]!r})")


MASK = "4 3 0.25 0.25 -0.375 -0.25\n.##.\n####\n.##.\n"   # 8 cells


def section_paths():
    # the namelist lives in sub/, its mask beside it; a decoy mask of another
    # size in the working folder must not be taken
    write(os.path.join(folder, "sub", "m.nml"),
          "&patch shape='mask', mask_file='m.mask' /\n&solver target_error=0 /\n&output traction_file='m.trac' /\n")
    write(os.path.join(folder, "sub", "m.mask"), MASK)
    write(os.path.join(folder, "m.mask"), "2 1 0.25 0.25 0 0\n##\n")
    proc = run(["sub/m.nml"])
    kc.check(proc.returncode == 0, f"single run from the parent folder finds sub/m.mask ({proc.stderr.strip()})")
    rows = kc.read_table(os.path.join(folder, "m.tab")) if proc.returncode == 0 else []
    kc.check(rows and rows[0]["n"] == 8, f"single run: the mask beside the namelist (8 cells) "
             f"({rows[0]['n'] if rows else None})")
    kc.check(os.path.exists(os.path.join(folder, "sub", "m.trac")),
             "single run: traction_file written beside the namelist")
    kc.check(os.path.exists(os.path.join(folder, "m.tab")),
             "single run: the default table (no table_file) stays in the working folder")
    # explicit table_file: relative to the namelist's folder as well
    write(os.path.join(folder, "sub", "t.nml"), "&patch mx=8, my=8 /\n&output table_file='t_out.tab' /\n")
    proc = run(["sub/t.nml"])
    kc.check(proc.returncode == 0 and os.path.exists(os.path.join(folder, "sub", "t_out.tab")),
             f"single run: table_file written beside the namelist ({proc.stderr.strip()})")
    # the same namelist through --estimate-memory and --batch, from two working folders
    for cwd in (folder, os.path.join(folder, "sub")):
        rel = os.path.relpath(os.path.join(folder, "sub", "m.nml"), cwd)
        est = run(["--estimate-memory", rel], cwd=cwd)
        kc.check(est.returncode == 0, f"--estimate-memory {rel} from {os.path.basename(cwd)}: exit 0 "
                 f"({est.stderr.strip()})")
        single = run([rel], cwd=cwd)
        kc.check(single.returncode == 0, f"single {rel} from {os.path.basename(cwd)}: exit 0 ({single.stderr.strip()})")
    write(os.path.join(folder, "l.list"), "sub/m.nml\n")
    proc = run(["--batch", "l.list"])
    rows = kc.read_table(os.path.join(folder, "l.tab")) if proc.returncode == 0 else []
    kc.check(rows and rows[0]["n"] == 8, f"--batch: the same 8 cells ({proc.stderr.strip()})")
    # the shipped examples, --estimate-memory and --batch from another folder;
    # on a copy of input/ (with shared/ beside it as in the repository's
    # parent), because their traction files are written beside the namelists
    inputs, shared = kc.copy_inputs(folder)
    examples = sorted(f for f in os.listdir(inputs) if f.endswith(".nml"))
    out = os.path.join(folder, "out")
    os.makedirs(out)
    for name in examples:
        if "contact" in name and not shared:
            kc.check(False, f"{name}: needs ../shared/contact-samples beside the repository")
            continue
        path = os.path.join(inputs, name)
        est = run(["--estimate-memory", path], cwd=out)
        kc.check(est.returncode == 0, f"--estimate-memory input/{name} from another folder ({est.stderr.strip()})")
    # one batch table holds one kind: the single patches in one list, the
    # contact table (&wheel_rail; two shifts at target 1e-2 here, for time) in another
    tables = [n for n in examples if "&wheel_rail" in open(os.path.join(inputs, n)).read()]
    write(os.path.join(out, "examples.list"), "".join(os.path.join(inputs, n) + "\n" for n in examples
                                                      if (shared or "contact" not in n) and n not in tables))
    proc = run(["--batch", "examples.list"], cwd=out)
    kc.check(proc.returncode == 0, f"--batch of the shipped examples: exit 0 ({proc.stderr.strip()[:300]})")
    kc.check(tables == ["s1002_uic60.nml"], f"the shipped contact tables: {tables}")
    if shared and tables:
        text = open(os.path.join(inputs, tables[0])).read()
        for old, new in kc.S1002_FAST.items():
            text = text.replace(old, new)
        write(os.path.join(inputs, "s1002_fast.nml"), text + "&solver target_error = 1e-2 /\n")
        write(os.path.join(out, "tables.list"), os.path.join(inputs, "s1002_fast.nml") + "\n")
        proc = run(["--batch", "tables.list"], cwd=out)
        kc.check(proc.returncode == 0 and os.path.exists(os.path.join(out, "s1002_fast.wr")),
                 f"--batch of the contact table example from another folder: its .wr ({proc.stderr.strip()[:300]})")


def section_given():
    cases = {
        "mx0": ("&patch mx=0 /\n", ("mx = 0",)),
        "my0": ("&patch my=0 /\n", ("my = 0",)),
        "maskmx0": ("&patch shape='mask', mask_rows='##', dx=1, dy=1, mx=0 /\n", ("mx = 0",)),
        "spin_colloc": ("&patch mx=10, my=10 /\n&solver scheme='collocation', spin_shift=0.2 /\n",
                        ("spin_shift", "collocation")),
        "alpha_default": ("&patch mx=10, my=10 /\n&solver alpha=0.3 /\n", ("alpha", "backward")),
        "alpha_backward": ("&patch mx=10, my=10 /\n&solver scheme='backward', alpha=0.3 /\n",
                           ("alpha", "backward")),
        "semi_mask": ("&patch shape='mask', mask_rows='##', dx=1, dy=1, semi_a=2 /\n", ("semi_a", "mask")),
        "x0_maskfile": ("&patch shape='mask', mask_file='g.mask', x0=5 /\n", ("x0", "g.mask")),
        "tol_dense": ("&patch mx=10, my=10 /\n&solver method='dense', tolerance=1e-9 /\n", ("tolerance", "dense")),
        "restart_dense": ("&patch mx=10, my=10 /\n&solver method='dense', restart=20 /\n", ("restart", "dense")),
        "refine_iter": ("&patch mx=10, my=10 /\n&solver method='iterative', refine='always' /\n",
                        ("refine", "iterative")),
        "levels_noext": ("&patch mx=10, my=10 /\n&solver extrapolate_levels=2 /\n", ("extrapolate_levels", "extrapolate")),
    }
    write(os.path.join(folder, "g.mask"), "2 1 0.25 0.25 0 0\n##\n")
    for name, (text, words) in cases.items():
        rc, out, err, table = kc.run(text, folder, name, expect_ok=False)
        kc.check(rc == 2, f"{name}: refused with exit 2 (got {rc})")
        one_error_line(subprocess.CompletedProcess([], rc, out, err), name, *words)
        kc.check(not os.path.exists(os.path.join(folder, name + ".tab")), f"{name}: no table written")
    # what stays allowed: spin_shift with the backward scheme, alpha with collocation,
    # x0 equal to the mask file's header, the default grid when mx is left out
    ok = {
        "spin_backward": "&patch mx=10, my=10 /\n&solver scheme='backward', spin_shift=0.2 /\n",
        "alpha_colloc": "&patch mx=10, my=10 /\n&solver scheme='collocation', alpha=0.3 /\n",
        "spin_default": "&patch mx=10, my=10 /\n&solver spin_shift=0.2 /\n",
        "x0_same": "&patch shape='mask', mask_file='g.mask', x0=0 /\n",
        "default_grid": "&patch semi_a=1 /\n&solver target_error=0 /\n",
        # a group after another's / on the same line (issue 45: G = 1 was used, exit 0)
        "one_line": "&patch semi_a = 2, semi_b = 1 / &material g = 5, nu = 0.3 /\n",
        "one_line_end": "&patch semi_a = 2, semi_b = 1 &end &material g = 5, nu = 0.3 /",
    }
    for name, text in ok.items():
        rc, out, err, table = kc.run(text, folder, name, expect_ok=False)
        kc.check(rc == 0, f"{name}: accepted ({err.strip()})")
        if name == "default_grid" and table:
            kc.check(table[0]["mx"] == 60 and table[0]["my"] == 60, "default grid 60 x 60 when mx, my are left out")
        if name.startswith("one_line") and table:
            kc.check(table[0]["g"] == 5 and table[0]["nu"] == 0.3 and abs(table[0]["c"] - 2 ** 0.5) < 1e-12,
                     f"{name}: both groups of the line read (g {table[0]['g']}, nu {table[0]['nu']}, c {table[0]['c']})")


def section_spin():
    # the same kidney-like patch at the origin and shifted far away (profile coordinates)
    rows = ["..####..", ".######.", "########", "#######.", ".#####..", "..###..."]
    mask_rows = ", ".join(f"'{r}'" for r in rows)

    def patch(x0, y0):
        return f"&patch shape='mask', mask_rows={mask_rows}, dx=0.5, dy=0.5, x0={x0}, y0={y0} /\n"

    rc, out, err, near = kc.run(patch(-1.75, -1.25), folder, "near", expect_ok=False)
    kc.check(rc == 0, f"patch around the origin solves ({err.strip()})")
    rc, out, err, far = kc.run(patch(1e6, 3.0), folder, "far", expect_ok=False)
    kc.check(rc == 0, f"patch at x0 = 1e6 solves ({err.strip()})")
    if not (near and far):
        return
    n, f = near[0], far[0]
    kc.check("xc" in f and "yc" in f, "table columns xc, yc (centroid)")
    cols = open(os.path.join(folder, "far.tab")).read().splitlines()
    header = [l for l in cols if l.startswith("#")][-1][1:].split()
    kc.check(header[-2:] == ["xc", "yc"], f"xc, yc appended at the end of the columns ({header[-3:]})")
    # centroid of the shifted patch: 1e6 + 1.75 + (centroid of the near one)
    if "xc" in f and "xc" in n:
        kc.close(f["xc"] - n["xc"], 1e6 + 1.75, 1e-9, "xc moves with the patch")
        kc.close(f["yc"] - n["yc"], 4.25, 1e-9, "yc moves with the patch")
    kc.check("centroid" in out, "the summary prints the centroid")
    kc.check(re.search(r"warning:.*origin.*outside", err) is not None,
             f"a warning when the origin lies outside the patch's bounding box ({err.strip()[:200]})")
    rc, out, err, _ = kc.run(patch(-1.75, -1.25), folder, "near2", expect_ok=False)
    kc.check("outside" not in err, "no such warning for a patch around the origin")
    # spin_centre = 'centroid': the far patch gives the same coefficients as the near one
    # about its own centroid; 'point' with coordinates likewise
    rc, out, err, farc = kc.run(patch(1e6, 3.0) + "&solver spin_centre='centroid' /\n", folder, "farc",
                                expect_ok=False)
    rc2, out2, err2, nearc = kc.run(patch(-1.75, -1.25) + "&solver spin_centre='centroid' /\n", folder, "nearc",
                                    expect_ok=False)
    kc.check(rc == 0 and rc2 == 0, f"spin_centre = 'centroid' accepted ({err.strip()} {err2.strip()})")
    if farc and nearc:
        scale = max(abs(nearc[0]["f33"]), 1.0)
        for c in ("f11", "f22", "f23", "f32", "f13", "f31", "f33"):
            # the operator depends on cell offsets only; the coordinates of the far
            # patch (1e6) carry about 1e-16 * 1e6 = 1e-10 relative rounding
            kc.check(abs(farc[0][c] - nearc[0][c]) <= 1e-8 * scale,
                     f"centroid spin centre: {c} independent of where the patch lies "
                     f"({farc[0][c]:.10g} vs {nearc[0][c]:.10g})")
        kc.check("outside" not in err, "no origin warning with spin_centre = 'centroid'")
    xc, yc = (n["xc"], n["yc"])
    rc, out, err, farp = kc.run(patch(1e6, 3.0) + f"&solver spin_centre='point', spin_centre_x={1e6 + 1.75 + xc!r}, "
                                f"spin_centre_y={4.25 + yc!r} /\n", folder, "farp", expect_ok=False)
    kc.check(rc == 0 and farp and farc and abs(farp[0]["f33"] - farc[0]["f33"]) <= 1e-8 * abs(farc[0]["f33"]),
             f"spin_centre = 'point' at the centroid equals 'centroid' ({err.strip()})")
    for text, words in (("&solver spin_centre='middle' /\n", ("spin_centre", "middle")),
                        ("&solver spin_centre='point', spin_centre_x=1 /\n", ("spin_centre_y",)),
                        ("&solver spin_centre_x=1, spin_centre_y=0 /\n", ("spin_centre_x", "point"))):
        rc, out, err, _ = kc.run(patch(0, 0) + text, folder, "badspin", expect_ok=False)
        kc.check(rc == 2 and words[0] in err, f"{text.strip()}: refused ({err.strip()})")


def section_extrap():
    # the default 60 x 60 circle with extrapolate: 60, 120, 240 per direction.
    # At 240 x 240 the dense matrix would need 61 GiB; 'auto' takes the
    # iterative path there, which needs well under 1 GiB. Solving all three
    # levels takes minutes, so the check runs with the memory as it is and a
    # smaller study (30 x 30, ratio 2: 30, 60, 120) is solved end to end.
    est = run(["--estimate-memory", write_and(folder, "e60.nml", "&solver extrapolate=.true. /\n"),
               write_and(folder, "i240.nml", "&patch mx=240, my=240 /\n&solver method='iterative' /\n")])
    fields = [l.rsplit(" ", 2) for l in est.stdout.strip().splitlines()]
    ok = est.returncode == 0 and len(fields) == 2
    kc.check(ok and fields[0][2] == "iterative" and int(fields[0][1]) == int(fields[1][1]),
             f"60 x 60 extrapolate: the estimate is that of its finest level, 240 x 240 iterative ({fields})")
    kc.check(ok and int(fields[0][1]) < 2 * 2**30, "and under 2 GiB")
    # the whole default-grid study on the iterative path (60, 120, 240 x 240)
    rc, out, err, table = kc.run("&solver extrapolate=.true., method='iterative' /\n", folder, "e60i",
                                 expect_ok=False)
    kc.check(rc == 0 and table and table[0]["mx"] == 240,
             f"60 x 60 extrapolate with the iterative solver runs to 240 x 240 ({err.strip()[:300]})")
    # a study that does not fit on its path is still refused before any work:
    # the whole dense matrix of the 240 x 240 level (90,000 unknowns, 65 GB)
    rc, out, err, table = kc.run("&solver extrapolate=.true., method='dense', split_systems=.false. /\n", folder,
                                 "e60d", expect_ok=False)
    kc.check(rc == 2 and "extrapolation level 3" in err and "GiB" in err,
             f"method = 'dense' unsplit at 240 x 240 is refused before any work ({err.strip()[:200]})")


def write_and(dirname, name, text):
    write(os.path.join(dirname, name), text)
    return name


def section_newline():
    for name, text in (("nonl", "&patch semi_a=2, mx=10, my=10 /"),
                       ("nonl2", "&patch mx=10, my=10 /\n&material nu=0.3 /"),
                       ("nonl_comment", "&patch mx=10, my=10 /\n! the end")):
        rc, out, err, table = kc.run(text, folder, name, expect_ok=False)
        kc.check(rc == 0, f"{name}: a last line without newline is read ({err.strip()})")
        if name == "nonl" and table:
            kc.close(table[0]["c"], 2 ** 0.5, 1e-12, "nonl: semi_a = 2 was read (c = sqrt(2))")
        if name == "nonl2" and table:
            kc.close(table[0]["nu"], 0.3, 1e-12, "nonl2: nu = 0.3 of the last group was read")
    rc, out, err, table = kc.run("&patch semi_a=2", folder, "noslash", expect_ok=False)
    kc.check(rc == 2 and "closing /" in err, f"a group without its / is still refused ({err.strip()})")


def section_memlimit():
    # under ulimit -v (RLIMIT_AS) of 1 GiB a 90 x 90 dense case (16,200 unknowns,
    # 2 GiB matrix) must be refused or routed, never die in an allocation
    limit = 1 << 30

    def limited():
        resource.setrlimit(resource.RLIMIT_AS, (limit, limit))

    write(os.path.join(folder, "big.nml"), "&patch mx=90, my=90 /\n&solver method='dense', split_systems=.false. /\n")
    proc = subprocess.run([kc.KCREEP, "big.nml"], cwd=folder, capture_output=True, text=True, preexec_fn=limited)
    kc.check(proc.returncode in (2, 3), f"dense 90 x 90 unsplit under a 1 GiB RLIMIT_AS: exit 2 or 3 "
             f"(got {proc.returncode})")
    one_error_line(proc, "dense under RLIMIT_AS", "GiB")
    kc.check("Backtrace" not in proc.stderr and "Error termination" not in proc.stderr, "no runtime backtrace")
    # auto: routed to the iterative path, which fits
    write(os.path.join(folder, "auto.nml"), "&patch mx=90, my=90 /\n")
    proc = subprocess.run([kc.KCREEP, "auto.nml"], cwd=folder, capture_output=True, text=True, preexec_fn=limited)
    kc.check(proc.returncode == 0 and "iterative" in proc.stdout,
             f"auto 90 x 90 under 1 GiB: solved on the iterative path ({proc.returncode}: {proc.stderr.strip()[:200]})")
    # a tight address-space limit: OpenBLAS, refused a work buffer by mmap,
    # retries for ever (measured: dgetrf maps 128 MiB at once), so kcreep must
    # leave it room or refuse; either way it ends, with exit 0 or one line
    limit2 = 300 << 20

    def tight():
        resource.setrlimit(resource.RLIMIT_AS, (limit2, limit2))

    write(os.path.join(folder, "mid.nml"), "&patch mx=60, my=60 /\n&solver method='dense' /\n")
    try:
        proc = subprocess.run([kc.KCREEP, "mid.nml"], cwd=folder, capture_output=True, text=True, preexec_fn=tight,
                              env=dict(os.environ, OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1"), timeout=60)
        rc, err = proc.returncode, proc.stderr
    except subprocess.TimeoutExpired:
        rc, err = "timeout (hung)", ""
    kc.check(rc in (0, 2, 3) and "Backtrace" not in err and "Error termination" not in err,
             f"dense 60 x 60 under a 300 MiB RLIMIT_AS ends: exit 0, 2 or 3 ({rc}: {err.strip()[:300]})")
    if rc in (2, 3):
        one_error_line(proc, "dense 60 x 60 under 300 MiB", "GiB")


def section_estimate():
    write(os.path.join(folder, "a.nml"), "&patch mx=20, my=20 /\n")
    write(os.path.join(folder, "bad.nml"), "&patch shape='circle' /\n")
    write(os.path.join(folder, "c d.nml"), "&patch mx=30, my=30 /\n")
    proc = run(["--estimate-memory", "a.nml", "bad.nml", "missing.nml", "c d.nml"])
    lines = proc.stdout.strip().splitlines()
    kc.check(proc.returncode == 2, f"exit 2 when some files could not be estimated ({proc.returncode})")
    kc.check(len(lines) == 2, f"one line per estimated file on standard output ({lines})")
    pat = re.compile(r"^(.+) (\d+) (dense|iterative)$")
    parsed = [pat.match(l) for l in lines]
    kc.check(all(parsed) and [p.group(1) for p in parsed] == ["a.nml", "c d.nml"],
             f"lines 'FILE BYTES PATH' in argument order ({lines})")
    if all(parsed) and len(parsed) == 2:
        kc.check(int(parsed[1].group(2)) > int(parsed[0].group(2)) > 0, "bytes grow with the grid")
    err = proc.stderr.strip().splitlines()
    kc.check(len(err) == 2 and all(l.startswith("kcreep: error: ") for l in err)
             and "bad.nml" in err[0] and "missing.nml" in err[1],
             f"one error line per bad file, in order, the others still estimated ({err})")
    ok = run(["--estimate-memory", "a.nml"])
    kc.check(ok.returncode == 0 and pat.match(ok.stdout.strip()), f"all good: exit 0 ({ok.stdout.strip()})")
    # the estimate against the measured peak (GNU time): at least the peak
    # RSS (the program itself included) and at most 1.2 times it. Measured
    # (src/solve/kcreep_solve_memory.f90 has the model and its fit): circle
    # iterative 160 x 160 57.4 MB against 49.5 MB (1.16; 60 to 600 across:
    # 1.10 to 1.18), dense 60 x 60 88.9 against 86.8 MB (1.02; 40 to 100
    # across: 1.005 to 1.03); before: iterative 76.9 against 49.8 (1.55).
    if not os.path.exists("/usr/bin/time"):
        kc.check(False, "/usr/bin/time is needed (Debian package 'time', scripts/setup.sh installs it)")
        return
    for name, text in (("it160", "&patch mx=160, my=160 /\n&solver method='iterative' /\n"),
                       ("d60", "&patch mx=60, my=60 /\n&solver method='dense' /\n")):
        write(os.path.join(folder, name + ".nml"), text)
        est = run(["--estimate-memory", name + ".nml"])
        bytes_ = int(est.stdout.split()[-2]) if est.returncode == 0 else 0
        rss, seconds, proc = peak_rss([kc.KCREEP, name + ".nml"])
        kc.check(proc.returncode == 0 and rss is not None and rss <= bytes_ <= 1.2 * rss,
                 f"{name}: estimate {bytes_ / 1e6:.1f} MB against peak RSS {(rss or 0) / 1e6:.1f} MB "
                 f"(RSS <= estimate <= 1.2 RSS)")
    # a grid too big for the memory is refused before the work: 2000 x 2000
    # iterative (7.3 GB) under a 2 GiB address space. Measured: 0.11 s and
    # 91 MB peak (the patch itself); before, 1.4 s and 1.31 GB (the operator
    # table and the solve plan were built first)
    write(os.path.join(folder, "huge.nml"), "&patch mx=2000, my=2000 /\n&solver method='iterative' /\n")
    limit = 2 << 30
    rss, seconds, proc = peak_rss([kc.KCREEP, "huge.nml"],
                                  preexec_fn=lambda: resource.setrlimit(resource.RLIMIT_AS, (limit, limit)))
    kc.check(proc.returncode == 2 and "GiB" in proc.stderr and "iterative" in proc.stderr,
             f"2000 x 2000 iterative under 2 GiB: refused, exit 2 ({proc.returncode}: {proc.stderr.strip()[:200]})")
    kc.check(rss is not None and rss < 200e6 and seconds < 0.6,
             f"and refused quickly and small: {seconds:.2f} s CPU (< 0.6), peak RSS {(rss or 0) / 1e6:.0f} MB (< 200)")


def peak_rss(command, **kw):
    """Peak RSS in bytes (GNU time -v), CPU seconds (user + system) and the process.
    CPU time, not wall: a loaded machine stretches the wall clock, not the work."""
    proc = subprocess.run(["/usr/bin/time", "-v"] + command, cwd=folder, capture_output=True, text=True,
                          env=dict(os.environ, OPENBLAS_NUM_THREADS="1"), **kw)
    m = re.search(r"Maximum resident set size \(kbytes\): (\d+)", proc.stderr)
    cpu = re.findall(r"(?:User|System) time \(seconds\): ([\d.]+)", proc.stderr)
    seconds = sum(float(c) for c in cpu) if len(cpu) == 2 else float("inf")
    return (int(m.group(1)) * 1024 if m else None), seconds, proc


def section_lock():
    # a batch of cases that take a moment each; a second batch on the same table
    # while the first runs is refused at once, and the first finishes untouched
    names = []
    for k in range(6):
        write(os.path.join(folder, f"c{k}.nml"), f"&patch semi_b={0.5 + 0.05 * k}, mx=44, my=44 /\n"
              "&solver method='dense', split_systems=.false. /\n")
        names.append(f"c{k}.nml")
    write(os.path.join(folder, "slow.list"), "\n".join(names) + "\n")
    first = subprocess.Popen([kc.KCREEP, "--batch", "slow.list", "t.tab"], cwd=folder,
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    deadline = time.time() + 60
    while not os.path.exists(os.path.join(folder, "t.tab.partial")) and time.time() < deadline:
        time.sleep(0.05)
    t0 = time.time()
    second = run(["--batch", "slow.list", "t.tab"], timeout=120)
    waited = time.time() - t0
    out, err = first.communicate(timeout=600)
    running = first.returncode is not None
    kc.check(second.returncode != 0, f"second batch on the same table: refused (exit {second.returncode})")
    one_error_line(second, "second batch", "t.tab.partial")
    # refusing means not running any case: far less than one case's time (about 1 s here)
    kc.check(waited < 0.5 and "1/6" not in second.stdout, f"refused at once ({waited:.2f} s, {second.stdout.strip()!r})")
    kc.check(running and first.returncode == 0, f"the first batch completes (exit {first.returncode}: {err.strip()})")
    rows = kc.read_table(os.path.join(folder, "t.tab")) if first.returncode == 0 else []
    kc.check([r["case"] for r in rows] == [n[:-4] for n in names], f"its table is whole ({len(rows)} rows)")
    # and afterwards the lock is free again
    again = run(["--batch", "slow.list", "t2.tab"])
    kc.check(again.returncode == 0, "a later batch runs")


def section_names():
    write(os.path.join(folder, "a", "case.nml"), "&patch semi_b=0.5, mx=10, my=10 /\n")
    write(os.path.join(folder, "b", "case.nml"), "&patch semi_b=0.8, mx=10, my=10 /\n")
    write(os.path.join(folder, "top.nml"), "&patch mx=10, my=10 /\n")
    write(os.path.join(folder, "two.list"), "a/case.nml\n./b/case.nml\ntop.nml\n" +
          os.path.join(folder, "a", "case.nml") + "\n")
    proc = run(["--batch", "two.list"])
    rows = kc.read_table(os.path.join(folder, "two.tab")) if proc.returncode == 0 else []
    names = [r["case"] for r in rows]
    kc.check(names == ["a/case", "b/case", "top", "a/case"],
             f"cases named by their path relative to the list ({names}; {proc.stderr.strip()})")
    # two cases writing one traction file: refused before any work
    write(os.path.join(folder, "a", "t.nml"), "&patch mx=10, my=10 /\n&output traction_file='../same.trac' /\n")
    write(os.path.join(folder, "b", "t.nml"), "&patch mx=12, my=12 /\n&output traction_file='../same.trac' /\n")
    write(os.path.join(folder, "clash.list"), "a/t.nml\nb/t.nml\n")
    proc = run(["--batch", "clash.list"])
    kc.check(proc.returncode == 2, f"two cases with the same traction_file: exit 2 ({proc.returncode})")
    one_error_line(proc, "traction clash", "traction_file", "a/t.nml", "b/t.nml")
    kc.check(not os.path.exists(os.path.join(folder, "same.trac")) and
             not os.path.exists(os.path.join(folder, "clash.tab")) and
             not os.path.exists(os.path.join(folder, "clash.tab.partial")), "nothing written")


SECTIONS = {"paths": section_paths, "given": section_given, "spin": section_spin, "extrap": section_extrap,
            "newline": section_newline, "memlimit": section_memlimit, "estimate": section_estimate,
            "lock": section_lock, "names": section_names}
if SECTION not in SECTIONS:
    sys.exit(f"usage: test_user_defects.py KCREEP SECTION ({', '.join(SECTIONS)})")
SECTIONS[SECTION]()
kc.finish()
