#!/usr/bin/env python3
"""kcreep's numerical-stability suite (standard library only).

Runs kcreep on stiff and extreme cases -- aspect ratios, Poisson's ratios,
collocation points near the singular edges, very fine and very coarse
grids, awkward masks, extreme units -- and judges each one:

  fails     kcreep gave no usable result (non-zero exit, a non-finite
            coefficient), or a measured problem went unflagged: verdict 'ok'
            while berr > BERR_STABLE, or while a reference check fails
            (units: normalised coefficients differ from the unit case by
            more than UNITS_REL; ellipses: more than KALKER_REL from
            Kalker's table)
  degraded  kcreep's own verdict is not 'ok': it printed numbers with a
            warning (degenerate / nonphysical / ill-conditioned / inaccurate)
  stable    verdict 'ok', berr <= BERR_STABLE and the reference checks pass

  stability.py --kcreep build/kcreep [--quick] [--markdown docs/stability.md] [--table FILE]

--quick runs the subset that CTest runs (about half a minute); exit status 1
when any case fails.
"""
import argparse
import math
import os
import shutil
import subprocess
import sys
import tempfile
import time

BERR_STABLE = 1e-12   # = kcreep's inaccurate limit; measured: every case has berr <= 8.4e-16
UNITS_REL = 1e-12     # measured: unit changes move c11, c22, c23 by <= 2.3e-15
KALKER_REL = 0.25     # measured discretisation error on these grids: up to 18.8 % (C23, collocation, 16 across)


def nml(patch, material="", solver="", output=""):
    # method='dense': the suite judges the LU (rcond, backward error, refinement);
    # 'auto' would hand the larger cases to GMRES, which has neither.
    # The suite judges each discretisation on its own grid: target_error = 0
    # (no error-control levels) and the paper's scheme unless the case names one.
    extra = "" if "scheme" in solver else "scheme='collocation', "
    return (f"&patch {patch} /\n&material {material} /\n&solver method='dense', target_error=0, {extra}{solver} /\n"
            f"&output {output} /\n")


def mask_rows(rows):
    return ", ".join(f"'{r}'" for r in rows)


def ellipse(a, b, mx, my):
    return f"semi_a={a}, semi_b={b}, mx={mx}, my={my}"


def inline(rows, dx=1.0, dy=1.0, centred=True):
    """An inline mask patch, centred on the origin unless told otherwise."""
    mx, my = len(rows[0]), len(rows)
    x0 = -(mx - 1) * dx / 2 if centred else 0.0
    y0 = -(my - 1) * dy / 2 if centred else 0.0
    return f"shape='mask', mask_rows={mask_rows(rows)}, dx={dx!r}, dy={dy!r}, x0={x0!r}, y0={y0!r}"


def disc_rows(m, keep):
    """m x m rows of cells whose centre (u, v) in [-1, 1]^2 satisfies keep(u, v)."""
    rows = []
    for j in range(m):
        v = -1 + (2 * j + 1) / m
        rows.append("".join("#" if keep(-1 + (2 * i + 1) / m, v) else "." for i in range(m)))
    return rows


def cases(quick):
    """(group, name, namelist, reference) -- reference: None, 'kalker', or ('units', base name)."""
    out = []
    # aspect ratios: square cells, at least 8 (16 near a/b = 1) across the short axis
    ratios = [0.1, 1, 10] if quick else [0.02, 0.05, 0.1, 0.2, 0.5, 1, 2, 5, 10, 20, 50]
    for r in ratios:
        short = 12 if r < 0.1 or r > 10 else 16
        a, b = (r, 1.0) if r >= 1 else (1.0, 1 / r)
        mx, my = (round(short * r), short) if r >= 1 else (short, round(short / r))
        for scheme in ("collocation", "backward"):
            if quick and scheme == "backward" and r != 10:
                continue
            out.append(("aspect ratio", f"a/b={r:g} {scheme}", nml(ellipse(a, b, mx, my), "nu=0.25", f"scheme='{scheme}'"),
                        "kalker"))   # Kalker's table is checked only on grids of >= 12 cells across
    # Poisson's ratio
    for nu in ([0, 0.5] if quick else [0, 0.25, 0.49, 0.5]):
        for scheme in ("collocation", "backward"):
            out.append(("nu", f"nu={nu:g} {scheme}", nml(ellipse(1, 1, 30, 30), f"nu={nu}", f"scheme='{scheme}'"),
                        "kalker"))
    # collocation point near the singular edges and near 0
    for alpha in ([0.999, 1e-6] if quick else [0.5, 0.9, 0.99, 0.999, 1e-3, 1e-6, -0.5]):
        out.append(("alpha", f"alpha={alpha:g}", nml(ellipse(1, 1, 30, 30), "nu=0.25", f"alpha={alpha}"), "kalker"))
    # very coarse and very fine grids
    coarse = [("1 cell", ["#"]), ("2 cells", ["##"]), ("3 cells", ["###"]), ("2 x 2", ["##", "##"]),
              ("single row (20 x 1 cells)", ["#" * 20]), ("single column (1 x 20 cells)", ["#"] * 20)]
    for label, rows in (coarse[:3] + coarse[4:5] if quick else coarse):
        for scheme in ("collocation", "backward"):
            out.append(("coarse grid", f"{label} {scheme}", nml(inline(rows), "nu=0.25", f"scheme='{scheme}'"), None))
    for m in ([1, 3] if quick else [1, 2, 3]):
        out.append(("coarse grid", f"ellipse {m} x {m}", nml(ellipse(1, 1, m, m), "nu=0.25"), None))
    if not quick:
        for m in (60, 80, 100, 120):
            out.append(("fine grid", f"circle {m} x {m}", nml(ellipse(1, 1, m, m), "nu=0.25"), "kalker"))
    # awkward masks (24 x 24 cells on the unit square)
    m = 24
    masks = [
        ("L-shape (non-convex)", disc_rows(m, lambda u, v: u < 0 or v < 0)),
        ("C-shape (non-convex)", disc_rows(m, lambda u, v: u * u + v * v <= 1 and not (u > 0 and abs(v) < 0.35))),
        ("annulus (hole)", disc_rows(m, lambda u, v: 0.25 <= u * u + v * v <= 1)),
        ("two discs (disconnected)", disc_rows(m, lambda u, v: (u + 0.5) ** 2 + v * v <= 0.16 or (u - 0.5) ** 2 + v * v <= 0.16)),
        ("checkerboard", disc_rows(m, lambda u, v: (round((u + 1) * m / 2 - 0.5) + round((v + 1) * m / 2 - 0.5)) % 2 == 0)),
        ("stripes along x", disc_rows(m, lambda u, v: round((v + 1) * m / 2 - 0.5) % 2 == 0)),
        ("stripes across x", disc_rows(m, lambda u, v: round((u + 1) * m / 2 - 0.5) % 2 == 0)),
    ]
    for label, rows in (masks[:1] + masks[3:5] if quick else masks):
        for scheme in ("collocation", "backward"):
            out.append(("mask", f"{label} {scheme}", nml(inline(rows, 2 / m, 2 / m), "nu=0.25", f"scheme='{scheme}'"), None))
    # extreme units: the normalised coefficients must not move beyond round-off
    base = "units a=1 g=1"
    out.append(("units", base, nml(ellipse(1, 1, 24, 24), "nu=0.25, g=1"), "kalker"))
    for a in (1e-6, 1e3):
        for g in (1, 1e12):
            if quick and (a, g) != (1e-6, 1e12):
                continue
            out.append(("units", f"units a={a:g} g={g:g}", nml(ellipse(a, a, 24, 24), f"nu=0.25, g={g}"), ("units", base)))
    mbase = "units mask dx=1"
    rows = disc_rows(16, lambda u, v: u * u + 2 * v * v <= 1)
    out.append(("units", mbase, nml(inline(rows, 1.0, 1.0), "nu=0.3"), None))
    for d in (1e-6, 1e3):
        out.append(("units", f"units mask dx={d:g} g=1e12", nml(inline(rows, d, d), "nu=0.3, g=1e12"), ("units", mbase)))
    return out


def run_kcreep(kcreep, text, folder, name):
    path = os.path.join(folder, name + ".nml")
    with open(path, "w") as f:
        f.write(text)
    t0 = time.monotonic()
    proc = subprocess.run([kcreep, path, ], cwd=folder, capture_output=True, text=True)
    wall = time.monotonic() - t0
    result = {"exit": proc.returncode, "stderr": proc.stderr.strip(), "wall": wall}
    if proc.returncode != 0:
        return result
    cols, row = None, None
    warnings = []
    for line in open(os.path.join(folder, name + ".tab")):
        if line.startswith("# WARNING: "):
            warnings.append(line[11:].strip())
        elif line.startswith("# case "):
            cols = line[1:].split()
        elif not line.startswith("#"):
            row = line.split()
    for c, v in zip(cols, row):
        try:
            result[c] = float(v)
        except ValueError:
            result[c] = v
    for line in proc.stdout.splitlines():
        line = line.strip()
        if line.startswith("solve: relative residual"):
            parts = line.replace(",", " ").split()
            result["residual"] = float(parts[3])
            result["berr0"] = float(parts[8])
            result["refined"] = "(refined)" in line
    result["warnings"] = warnings
    return result


def judge(case, r, results):
    group, name, text, reference = case
    if r["exit"] != 0:
        return "fails", f"kcreep exit {r['exit']}: {r['stderr'][:80]}"
    coeffs = [r["c11"], r["c22"], r["c23"]]
    if not all(math.isfinite(c) for c in coeffs):
        return "fails", "non-finite coefficient"
    problems = []
    if not r["berr"] <= BERR_STABLE:   # NaN included
        problems.append(f"berr {r['berr']:.1e} > {BERR_STABLE:g}")
    if reference == "kalker":
        dev = max(abs(r[f"c{k}"] / r[f"klt{k}"] - 1) for k in ("11", "22", "23"))
        r["kalker_dev"] = dev
        if dev > KALKER_REL:
            problems.append(f"{100 * dev:.0f} % from Kalker's table")
    elif isinstance(reference, tuple):
        ref = results[reference[1]]
        dev = max(abs(r[c] / ref[c] - 1) for c in ("c11", "c22", "c23"))
        r["units_dev"] = dev
        if dev > UNITS_REL:
            problems.append(f"normalised coefficients moved by {dev:.1e} from the unit case")
    if r["verdict"] != "ok":
        return "degraded", "kcreep says " + r["verdict"] + (("; also " + "; ".join(problems)) if problems else "")
    if problems:
        return "fails", "unflagged: " + "; ".join(problems)
    return "stable", ""


def fmt(x, spec=".3e"):
    if isinstance(x, float):
        return "NaN" if math.isnan(x) else format(x, spec)
    return str(x)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--kcreep", required=True)
    ap.add_argument("--quick", action="store_true", help="the CTest subset")
    ap.add_argument("--markdown", help="write the report here (docs/stability.md)")
    ap.add_argument("--table", help="write a whitespace table of every case here")
    ap.add_argument("--refine-compare", action="store_true",
                    help="also run the stiff cases with refine = never / always / lapack")
    args = ap.parse_args()
    kcreep = os.path.abspath(args.kcreep)
    folder = tempfile.mkdtemp(prefix="kcreep-stability-")
    results, rows = {}, []
    counts = {"stable": 0, "degraded": 0, "fails": 0}
    try:
        for k, case in enumerate(cases(args.quick)):
            group, name, text, reference = case
            r = run_kcreep(kcreep, text, folder, f"s{k}")
            results[name] = r
            verdict, rule = judge(case, r, results)
            counts[verdict] += 1
            rows.append((case, r, verdict, rule))
            print(f"{verdict:8s} {group:12s} {name:38s} c11 {fmt(r.get('c11', math.nan), '.5g'):>9s} "
                  f"rcond {fmt(r.get('rcond', math.nan), '.1e')} berr {fmt(r.get('berr', math.nan), '.1e')} "
                  f"{r.get('verdict', '')} {rule}", flush=True)
        refine_rows = []
        if args.refine_compare:
            stiff = [c for c in cases(args.quick) if c[1] in (
                "alpha=0.999", "alpha=1e-06", "nu=0.5 collocation", "checkerboard collocation", "a/b=50 collocation",
                "a/b=0.02 collocation", "stripes across x collocation", "single row (20 x 1 cells) collocation",
                "circle 60 x 60")]
            for case in stiff:
                line = {"name": case[1]}
                for mode in ("never", "auto", "always", "lapack"):
                    text = case[2].replace("&solver ", f"&solver refine='{mode}', ", 1)
                    r = run_kcreep(kcreep, text, folder, "refine")
                    line[mode] = r
                refine_rows.append(line)
                print("refine", case[1], " ".join(
                    f"{m}: berr {line[m].get('berr', math.nan):.1e} c11 {line[m].get('c11', math.nan):.15g}"
                    for m in ("never", "auto", "always", "lapack")), flush=True)
    finally:
        shutil.rmtree(folder, ignore_errors=True)
    print(f"stability: {counts['stable']} stable, {counts['degraded']} degraded, {counts['fails']} fails")
    if args.table:
        with open(args.table, "w") as f:
            f.write("# group|case|grid|n|c11|c22|c23|rcond|residual|berr0|berr|kcreep_verdict|suite_verdict|rule\n")
            for case, r, verdict, rule in rows:
                f.write("|".join([case[0], case[1], f"{int(r.get('mx', 0))}x{int(r.get('my', 0))}", str(int(r.get('n', 0))),
                                  *(fmt(r.get(c, math.nan), '.10e') for c in ('c11', 'c22', 'c23', 'rcond', 'residual',
                                                                           'berr0', 'berr')),
                                  str(r.get("verdict", "-")), verdict, rule]) + "\n")
    if args.markdown:
        write_markdown(args.markdown, rows, counts, refine_rows, args.quick)
    sys.exit(1 if counts["fails"] else 0)


def write_markdown(path, rows, counts, refine_rows, quick):
    out = []
    out.append("## Cases\n")
    out.append("| group | case | grid | n | C11 | C22 | C23 | dev. | rcond | rel. residual | berr before | berr after | "
               "kcreep verdict | suite verdict |")
    out.append("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for case, r, verdict, rule in rows:
        dev = r.get("kalker_dev", r.get("units_dev"))
        dev_s = "" if dev is None else (f"{100 * dev:.1f} %" if "kalker_dev" in r else f"{dev:.1e}")
        out.append("| " + " | ".join([
            case[0], case[1], f"{int(r.get('mx', 0))} x {int(r.get('my', 0))}", str(int(r.get("n", 0))),
            fmt(r.get("c11", math.nan), ".5g"), fmt(r.get("c22", math.nan), ".5g"), fmt(r.get("c23", math.nan), ".5g"),
            dev_s, fmt(r.get("rcond", math.nan), ".1e"), fmt(r.get("residual", math.nan), ".1e"),
            fmt(r.get("berr0", math.nan), ".1e"), fmt(r.get("berr", math.nan), ".1e"),
            str(r.get("verdict", "exit %d" % r["exit"])), f"**{verdict}**" if verdict != "stable" else verdict]) + " |")
    out.append(f"\n{counts['stable']} stable, {counts['degraded']} degraded, {counts['fails']} fails"
               f"{' (quick subset)' if quick else ''}.\n")
    degraded = [(case, r, rule) for case, r, verdict, rule in rows if verdict != "stable"]
    if degraded:
        out.append("### What kcreep says about the degraded cases\n")
        for case, r, rule in degraded:
            said = "; ".join(r.get("warnings", [])) or r.get("stderr", "")
            out.append(f"- **{case[0]}, {case[1]}** ({rule}): {said}")
        out.append("")
    if refine_rows:
        out.append("## Refinement compared\n")
        out.append("Normwise backward error after the solve and C11 for each `&solver refine` mode "
                   "(never: LU only; auto: one step when berr > 100 eps; always: one step; "
                   "lapack: dgesvx with equilibration and dgerfs).\n")
        out.append("| case | never | auto | always | lapack (equilibrated) | max rel. change of C11, C22, C23 |")
        out.append("|---|---|---|---|---|---|")
        for line in refine_rows:
            base = line["never"]
            change = max(abs(line[m][c] / base[c] - 1) for m in ("auto", "always", "lapack") for c in ("c11", "c22", "c23")
                         if base.get(c) and math.isfinite(base[c]))
            out.append("| " + line["name"] + " | " + " | ".join(
                f"{line[m].get('berr', math.nan):.1e}" + (f" (rcond {line[m].get('rcond', math.nan):.1e})" if m == "lapack" else "")
                for m in ("never", "auto", "always", "lapack")) + f" | {change:.1e} |")
        out.append("")
    text = "\n".join(out) + "\n"
    # keep the hand-written head of the report (everything before '## Cases'), replace the rest
    head = ""
    if os.path.exists(path):
        old = open(path).read()
        if "## Cases" in old:
            head = old[:old.index("## Cases")]
    if not head:
        head = "# kcreep numerical stability\n\nGenerated by `scripts/stability.sh`.\n\n"
    with open(path, "w") as f:
        f.write(head + text)


if __name__ == "__main__":
    main()
