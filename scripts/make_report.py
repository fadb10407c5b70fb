#!/usr/bin/env python3
"""Write docs/convergence.md from its template and the study data.

    scripts/make_report.py           write docs/convergence.md
    scripts/make_report.py --check   exit 1 if docs/convergence.md is not what
                                     the template and the data give
    scripts/make_report.py --list    print the computed numbers
    scripts/make_report.py --help    this text

Every number in the report comes from docs/data/*.dat, which the study
scripts write with --docs (sweep_alpha.sh, sweep_n.sh, error_vs_time.sh).
The template docs/convergence.md.in holds the text; {{NAME}} is replaced by
a table or a number computed here.
"""
import math
import os
import statistics
import sys

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, here)
from richardson import read_table  # noqa: E402

REPO = os.path.dirname(here)
DATA = os.path.join(REPO, "docs", "data")
COEF = ("11", "22", "23")


def fnum(x):
    try:
        return float(x)
    except ValueError:
        return float("nan")


def pct(x, digits=2):
    return "n/a" if x != x else f"{100 * x:+.{digits}f} %"


def crossing(points):
    """alpha in (0, 1) where the ratio crosses 1 (linear interpolation), else nan."""
    pts = sorted((a, v) for a, v in points if 0 < a < 1 and v == v)
    for (a0, v0), (a1, v1) in zip(pts, pts[1:]):
        if (v0 - 1) * (v1 - 1) <= 0 and v0 != v1:
            return a0 + (1 - v0) * (a1 - a0) / (v1 - v0)
    return float("nan")


def alpha_section(values):
    rows = read_table(os.path.join(DATA, "sweep_alpha.dat"))
    series = {}
    for r in rows:
        ratio, grid, al = r["case"].split("_")
        key = (float(ratio[1:]), grid)
        series.setdefault(key, {"mx": r["mx"], "my": r["my"], "pts": []})
        series[key]["pts"].append((float(al[1:]), {c: fnum(r["c" + c]) / fnum(r["klt" + c]) for c in COEF}, r["verdict"]))
    out = ["| a/b | grid | dx/dy | f11/KLT, f22/KLT, f23/KLT at alpha = 0.5 | at alpha = 0 | "
           "alpha where f11, f22, f23 meet KLT | verdicts alpha <= 0 |", "|---|---|---|---|---|---|---|"]
    for (ratio, grid) in sorted(series, key=lambda k: (k[0], k[1] != "paper")):
        s = series[(ratio, grid)]
        mx, my = int(s["mx"]), int(s["my"])
        aspect = (2 * math.sqrt(ratio) / mx) / (2 / math.sqrt(ratio) / my)
        at = {a: v for a, v, _ in s["pts"]}
        half = at.get(0.5)
        zero = at.get(0.0)
        cross = [crossing([(a, v[c]) for a, v, _ in s["pts"]]) for c in COEF]
        verdicts = sorted({w for a, _, verd in s["pts"] if a <= 0 for w in verd.split(",")})
        key = f"r{ratio:g}_{grid}"
        for c, x in zip(COEF, cross):
            values[f"alpha_star{c}_{key}"] = f"{x:.2f}"
        if half:
            for c in COEF:
                values[f"alpha05_{c}_{key}"] = f"{half[c]:.4f}"
        out.append(f"| {ratio:g} | {grid} {mx} x {my} | {aspect:.2f} | "
                   + (", ".join(f"{half[c]:.4f}" for c in COEF) if half else "-") + " | "
                   + (", ".join(f"{zero[c]:.2g}" for c in COEF) if zero else "-") + " | "
                   + ", ".join("none" if x != x else f"{x:.2f}" for x in cross) + " | "
                   + " ".join(verdicts) + " |")
    return "\n".join(out)


def n_section(values):
    rows = read_table(os.path.join(DATA, "sweep_n.dat"))
    series = {}
    for r in rows:
        ratio, grid, scheme, m = r["case"].split("_")
        series.setdefault((float(ratio[1:]), grid, scheme), {})[int(m[1:])] = r
    meshes = sorted({m for s in series.values() for m in s})
    show = [m for m in meshes if m in (10, 20, 40, 60, 80)] or meshes
    out = ["| a/b | grid | scheme | " + " | ".join(f"M = {m}" for m in show) + " |",
           "|---|---|---|" + "---|" * len(show)]
    for key in sorted(series, key=lambda k: (k[0], k[1] != "paper", k[2] != "collocation")):
        ratio, grid, scheme = key
        cells = []
        for m in show:
            r = series[key].get(m)
            if r is None:
                cells.append("-")
                continue
            q = [fnum(r["c" + c]) / fnum(r["klt" + c]) - 1 for c in COEF]
            flag = "" if r["verdict"] == "ok" else f" ({r['verdict']})"
            cells.append(" / ".join(f"{100 * x:+.2f}" for x in q) + flag)
            tag = f"r{ratio:g}_{grid}_{scheme}_m{m}"
            for c, x in zip(COEF, q):
                values[f"klt{c}_{tag}"] = f"{100 * x:+.2f} %"
        out.append(f"| {ratio:g} | {grid} | {scheme} | " + " | ".join(cells) + " |")
    return "\n".join(out)


def richardson_section(values):
    rows = []
    with open(os.path.join(DATA, "richardson_sweep_n.dat")) as f:
        for line in f:
            if line.startswith("#") or not line.strip():
                continue
            w = line.split()
            rows.append(dict(series=w[0], m=(int(w[1]), int(w[2]), int(w[3])), coef=w[4],
                             f=[float(x) for x in w[5:8]], p=fnum(w[8]), f0=fnum(w[9]), klt=fnum(w[11])))
    out = ["| series | meshes | p (C11, C22, C23) | limit C11, C22, C23 | limit / Kalker - 1 |", "|---|---|---|---|---|"]
    groups = {}
    for r in rows:
        groups.setdefault((r["series"], r["m"]), {})[r["coef"]] = r
    for (series, m), g in sorted(groups.items(), key=lambda t: (t[0][0], t[0][1][2])):
        if m not in ((10, 20, 40), (20, 40, 80)):
            continue
        ps = ", ".join("-" if g[c]["p"] != g[c]["p"] else f"{g[c]['p']:.2f}" for c in ("c11", "c22", "c23"))
        f0 = ", ".join("-" if g[c]["f0"] != g[c]["f0"] else f"{g[c]['f0']:.4f}" for c in ("c11", "c22", "c23"))
        vs = ", ".join(pct(g[c]["f0"] / g[c]["klt"] - 1) for c in ("c11", "c22", "c23"))
        out.append(f"| {series} | {m[0]}/{m[1]}/{m[2]} | {ps} | {f0} | {vs} |")
        tag = f"{series}_{m[0]}_{m[1]}_{m[2]}"
        for c in ("c11", "c22", "c23"):
            values[f"p{c[1:]}_{tag}"] = "-" if g[c]["p"] != g[c]["p"] else f"{g[c]['p']:.2f}"
            values[f"f0{c[1:]}_{tag}"] = "-" if g[c]["f0"] != g[c]["f0"] else f"{g[c]['f0']:.4f}"
    return "\n".join(out)


def time_section(values):
    head, rows = [], []
    with open(os.path.join(DATA, "error_vs_time.dat")) as f:
        for line in f:
            if line.startswith("# reference"):
                head.append(line[2:].strip())
            elif not line.startswith("#") and line.strip():
                w = line.split()
                rows.append(dict(scheme=w[0], m=int(w[1]), n=int(w[2]), t=float(w[3]),
                                 c=[float(x) for x in w[4:7]], err=[float(x) for x in w[7:10]],
                                 klt=[float(x) for x in w[10:13]]))
    for line in head:
        name = line.split()[1]
        values[f"ref_{name}"] = line.split("=")[1].split("[")[0].strip()
    out = ["| scheme | grid | cells n | median time [s] | error C11, C22, C23 (vs reference) | vs Kalker |",
           "|---|---|---|---|---|---|"]
    for r in rows:
        out.append(f"| {r['scheme']} | {r['m']} x {r['m']} | {r['n']} | {r['t']:.3f} | "
                   + ", ".join(f"{100 * e:.2f} %" for e in r["err"]) + " | "
                   + ", ".join(f"{100 * e:+.2f} %" for e in r["klt"]) + " |")
        tag = f"{r['scheme']}_m{r['m']}"
        values[f"t_{tag}"] = f"{r['t']:.2f} s"
        for c, e in zip(COEF, r["err"]):
            values[f"err{c}_{tag}"] = f"{100 * e:.2f} %"
        values[f"errmax_{tag}"] = f"{100 * max(r['err']):.2f} %"
    by = {(r["scheme"], r["m"]): r for r in rows}
    if ("collocation", 60) in by and ("collocation", 80) in by:
        a, b = by[("collocation", 60)], by[("collocation", 80)]
        values["time_ratio_80_60_collocation"] = f"{b['t'] / a['t']:.1f}"
    if ("backward", 60) in by and ("backward", 80) in by:
        a, b = by[("backward", 60)], by[("backward", 80)]
        values["time_ratio_80_60_backward"] = f"{b['t'] / a['t']:.1f}"
    # cheapest run of each scheme with every error below 1 % and 0.5 %
    for target in (0.01, 0.005):
        for scheme in ("collocation", "backward"):
            ok = [r for r in rows if r["scheme"] == scheme and max(r["err"]) <= target]
            key = f"cheapest_{scheme}_{str(target).replace('0.', '')}"
            if ok:
                r = min(ok, key=lambda r: r["t"])
                values[key] = f"{r['m']} x {r['m']} ({r['t']:.2f} s, largest error {100 * max(r['err']):.2f} %)"
            else:
                values[key] = "none of the meshes run"
    return "\n".join(head and ["Reference (Richardson, both schemes):", ""] + [f"- {h}" for h in head] + [""]
                     + out)


def evt_rows():
    rows = {}
    with open(os.path.join(DATA, "error_vs_time.dat")) as f:
        for line in f:
            w = line.split()
            if line.startswith("#") or not w:
                continue
            rows[(w[0], int(w[1]))] = dict(t=float(w[3]), c=[float(x) for x in w[4:7]],
                                           err=[float(x) for x in w[7:10]], klt=[float(x) for x in w[10:13]])
    return rows


def texts(values):
    """The sentences whose numbers (and wording) follow from the data."""
    v = values
    rich = {}
    with open(os.path.join(DATA, "richardson_sweep_n.dat")) as f:
        for line in f:
            w = line.split()
            if not line.startswith("#") and w:
                rich[(w[0], int(w[1]), int(w[2]), int(w[3]), w[4])] = (fnum(w[8]), fnum(w[9]), fnum(w[11]))
    sweep = {r["case"]: r for r in read_table(os.path.join(DATA, "sweep_n.dat"))}
    evt = evt_rows()

    def klt_err(case, c):
        r = sweep[case]
        return fnum(r["c" + c]) / fnum(r["klt" + c]) - 1

    # convergence
    lines = []
    for scheme in ("collocation", "backward"):
        ps = []
        for tri in ((10, 20, 40), (15, 30, 60), (20, 40, 80)):
            got = [rich.get((f"r1_paper_{scheme}",) + tri + (c,)) for c in ("c11", "c22", "c23")]
            if all(got):
                ps.append(f"{'/'.join(map(str, tri))}: " + ", ".join("-" if g[0] != g[0] else f"{g[0]:.2f}" for g in got))
        lines.append(f"- {scheme}, circle, observed orders p of C11, C22, C23 — " + "; ".join(ps) + ".")
    errs = {m: [abs(klt_err(f"r1_paper_collocation_m{m}", c)) for c in COEF] for m in (20, 40, 80)}
    monotone = all(errs[20][i] > errs[40][i] > errs[80][i] for i in range(3))
    halving = [errs[40][i] / errs[80][i] for i in range(3)]
    lines.append(f"- The collocation error against KLT falls {'steadily' if monotone else 'but not monotonically'}: "
                 + ", ".join(f"C{c} {100 * errs[20][i]:.2f} % -> {100 * errs[40][i]:.2f} % -> {100 * errs[80][i]:.2f} %"
                             for i, c in enumerate(COEF))
                 + f" at M = 20, 40, 80 (ratio 40 -> 80: " + ", ".join(f"{x:.1f}" for x in halving)
                 + "; first order halves the error).")
    for scheme in ("collocation", "backward"):
        ps = []
        for tri in ((10, 20, 40), (15, 30, 60), (20, 40, 80)):
            got = [rich.get((f"r1_paper_{scheme}@area",) + tri + (c,)) for c in ("c11", "c22", "c23")]
            if all(got):
                ps.append(f"{'/'.join(map(str, tri))}: " + ", ".join("-" if g[0] != g[0] else f"{g[0]:.2f}" for g in got))
        lines.append(f"- {scheme}, circle, **normalised by the staircase area** (`@area`): orders " + "; ".join(ps) + ".")
    lines.append("- **The staircase spoils the raw sequence.** The cells whose centres lie in the ellipse cover an "
                 "area that differs from pi a b by an amount that jumps with the mesh (circle: "
                 + ", ".join(f"M = {m}: {100 * (4 * int(sweep[f'r1_paper_collocation_m{m}']['n']) / m / m / math.pi - 1):+.2f} %"
                             for m in (15, 20, 30, 40, 60, 80))
                 + "), and C11, C22 scale with the area (C23 with its power 3/2). The raw orders therefore scatter "
                   "(the `-` entries: the three values are not monotone). Normalising each mesh by its own area "
                   "(c^2 = area/pi, as kcreep does for masks) removes that noise: the sequences become monotone, "
                   "the observed order at 20/40/80 is about 0.7-1 (below first order: the traction is singular at the "
                   "trailing edge) and the two schemes extrapolate to the same limits.")
    lim = {}
    for scheme in ("collocation", "backward"):
        for c in ("c11", "c22", "c23"):
            lim[(scheme, c)] = rich.get((f"r1_paper_{scheme}@area", 20, 40, 80, c))
    if all(lim.values()):
        gaps = [lim[("collocation", c)][1] / lim[("backward", c)][1] - 1 for c in ("c11", "c22", "c23")]
        lines.append("- The two schemes' area-normalised limits (20/40/80, circle) are "
                     + ", ".join(f"C{c[1:]} {lim[('collocation', c)][1]:.4f} / {lim[('backward', c)][1]:.4f}"
                                 for c in ("c11", "c22", "c23"))
                     + " (collocation / backward), a difference of " + ", ".join(f"{100 * g:+.2f} %" for g in gaps)
                     + ". Two different discretisations agreeing this closely is the best evidence we have of the "
                       "continuum values; against KLT they are "
                     + ", ".join(f"{pct(lim[('collocation', c)][1] / lim[('collocation', c)][2] - 1)}" for c in ("c11", "c22", "c23"))
                     + " (section 4).")
    lines.append("- The paper's elongated cells (a/b = 5 on 80 x 80, dx/dy = 5) do not converge cleanly in either "
                 "form (collocation is `degenerate` at the coarser meshes); the near-square grids do better but "
                 "still scatter for a/b = 5. Use near-square cells.")
    v["CONVERGENCE_TEXT"] = "\n".join(lines)

    # error against time
    lines = []
    for scheme in ("collocation", "backward"):
        a, b = evt.get((scheme, 60)), evt.get((scheme, 80))
        if a and b:
            lines.append(f"- {scheme}: 60 x 60 takes {a['t']:.2f} s with errors "
                         + ", ".join(f"{100 * e:.2f} %" for e in a["err"])
                         + f"; 80 x 80 takes {b['t']:.2f} s ({b['t'] / a['t']:.1f} times as long) with "
                         + ", ".join(f"{100 * e:.2f} %" for e in b["err"]) + " (C11, C22, C23 against the reference).")
    lines.append(f"- Cheapest run with every error below 1 %: collocation {v['cheapest_collocation_01']}; "
                 f"backward {v['cheapest_backward_01']}. Below 0.5 %: collocation {v['cheapest_collocation_005']}; "
                 f"backward {v['cheapest_backward_005']}.")
    ext = [(k, r) for k, r in evt.items() if k[0].endswith("+extrapolate")]
    for (scheme, m), r in sorted(ext):
        lines.append(f"- `extrapolate = .true.` with {scheme.split('+')[0]} from {m // 4} x {m // 4} "
                     f"(levels {m // 4}, {m // 2}, {m}): {r['t']:.2f} s, errors "
                     + ", ".join(f"{100 * e:.2f} %" for e in r["err"]) + ".")
    v["TIME_TEXT"] = "\n".join(lines)

    # Kalker
    with open(os.path.join(DATA, "error_vs_time.dat")) as f:
        refs = [line for line in f if line.startswith("# reference")]
    parts = []
    for line in refs:
        name = line.split()[2]
        val = float(line.split("=")[1].split("+-")[0])
        unc = float(line.split("+-")[1].split("%")[0])
        klt = float(line.split("Kalker")[1].split()[0])
        parts.append(f"{name.upper()}: reference {val:.4f} +- {unc:.2f} %, KLT {klt:.2f} "
                     f"({100 * (klt / val - 1):+.2f} %)")
    v["KLT_TEXT"] = ("For the circle the Richardson reference (section 3) against KLT: " + "; ".join(parts)
                     + ". Where the gap exceeds both KLT's rounding and the reference's uncertainty, "
                       "a kcreep error 'against KLT' of a few tenths of a percent says as much about the table "
                       "as about kcreep: errors below about 0.5 % must be judged against the reference, not KLT.")

    # claims
    c60 = {r: [klt_err(f"r{r}_paper_collocation_m60", c) for c in COEF] for r in ("0.2", "1", "5")}
    b60 = {r: [klt_err(f"r{r}_paper_backward_m60", c) for c in COEF] for r in ("0.2", "1", "5")}
    within = lambda d: all(abs(d[r][0]) <= 0.01 and abs(d[r][1]) <= 0.01 for r in d)
    claims = [
        "1. *alpha = 0 is best for f11, f22*: **does not hold**; alpha = 0 gives f11 = f22 = 0 (section 1). "
        f"The best alpha for f11, f22 on the circle at 80 x 80 is about {v['alpha_star11_r1_paper']}.",
        f"2. *alpha = 0.5 is best for f23*: **not confirmed**; f23 meets KLT at alpha = {v['alpha_star23_r1_paper']} "
        f"(circle, 80 x 80), and at 0.5 it is off by {pct(float(v['alpha05_23_r1_paper']) - 1)}.",
        "3. *no convergence in N*: **does not hold** for kcreep; both schemes converge, at an observed order of "
        "about 0.7-1 once the staircase area is accounted for (section 2; the trailing-edge singularity of the "
        "traction slows convergence, it does not stop it). The raw sequence on an ellipse does look erratic "
        "between neighbouring meshes, which may be what the paper saw.",
        "4. *60 x 60 keeps f11 and f22 within 1 % of KLT*: collocation (alpha = 0.5), paper grid: "
        + "; ".join(f"a/b = {r}: {pct(c60[r][0])}, {pct(c60[r][1])}" for r in c60)
        + (" — **holds**" if within(c60) else " — **does not hold** for every ratio")
        + "; backward: " + "; ".join(f"a/b = {r}: {pct(b60[r][0])}, {pct(b60[r][1])}" for r in b60)
        + (" — holds." if within(b60) else " — not for every ratio."),
    ]
    a, b = evt.get(("collocation", 60)), evt.get(("collocation", 80))
    n60 = int(sweep["r1_paper_collocation_m60"]["n"])
    n80 = int(sweep["r1_paper_collocation_m80"]["n"])
    if a and b:
        ratio = b['t'] / a['t']
        dense_cube = (n80 / n60) ** 3
        if ratio >= 3:
            cost = "The cost factor is about as claimed or larger"
        else:
            cost = (f"The paper's factor is that of a dense LU (n^3: ({n80}/{n60})^3 = {dense_cube:.1f}); kcreep's "
                    "default `method = 'auto'` takes the FFT-accelerated iterative path at these sizes, whose time "
                    "grows about as n^1.3 (docs/performance.md), so 80 x 80 is no longer the expensive choice")
        claims.append(f"5. *80 x 80 costs about 4 times as much for 0.2 % less error*: measured {ratio:.1f} times "
                      f"the time with kcreep's default solver, and the "
                      f"collocation error falls by " + ", ".join(f"{100 * (x - y):.2f}" for x, y in zip(a["err"], b["err"]))
                      + f" percentage points (C11, C22, C23). {cost}; the gain "
                        "is larger than 0.2 % for the collocation scheme at alpha = 0.5.")
    v["CLAIMS_TEXT"] = "\n".join(claims)
    v["RECOMMENDATION_TEXT"] = recommendation(v, evt)


def recommendation(v, evt):
    """The cheapest setting of the error-against-time study that keeps every
    error (C11, C22, C23 against the reference) below 0.5 %, and the best
    single run below 1 %."""
    def describe(key, r):
        scheme, m = key
        if scheme.endswith("+extrapolate"):
            base = scheme.split("+")[0]
            setting = (f"`&solver scheme = '{base}', extrapolate = .true. /` on a {m // 4} x {m // 4} grid "
                       f"(levels {m // 4}, {m // 2}, {m})")
        else:
            setting = f"`&solver scheme = '{scheme}' /` on a {m} x {m} grid"
        return (setting + ": errors " + ", ".join(f"{100 * e:.2f} %" for e in r["err"])
                + f" (C11, C22, C23), {r['t']:.2f} s")
    out = []
    for target, label in ((0.005, "0.5 %"), (0.01, "1 %")):
        ok = [(k, r) for k, r in evt.items() if max(r["err"]) <= target]
        if ok:
            # times within 25 % of the cheapest are a tie on a shared machine: take the most accurate
            fastest = min(r["t"] for _, r in ok)
            k, r = min((kr for kr in ok if kr[1]["t"] <= 1.25 * fastest), key=lambda kr: max(kr[1]["err"]))
            out.append(f"- Cheapest with every error below {label} (times within 25 % count as equal; the most accurate of those): {describe(k, r)}.")
            v[f"recommended_{label.split()[0]}"] = describe(k, r)
        else:
            out.append(f"- No setting of the study keeps every error below {label}.")
    singles = [(k, r) for k, r in evt.items() if "+" not in k[0] and max(r["err"]) <= 0.01]
    if singles:
        k, r = min(singles, key=lambda kr: kr[1]["t"])
        out.append(f"- Cheapest single run (no extrapolation) below 1 %: {describe(k, r)}.")
    for key in (("collocation", 60), ("backward", 60)):
        if key in evt:
            out.append(f"- For comparison, {describe(key, evt[key])}.")
    return "\n".join(out)


def render():
    values = {}
    tables = {"TABLE_ALPHA": alpha_section(values), "TABLE_N": n_section(values),
              "TABLE_RICHARDSON": richardson_section(values), "TABLE_TIME": time_section(values)}
    values.update(tables)
    texts(values)
    with open(os.path.join(REPO, "docs", "convergence.md.in")) as f:
        text = f.read()
    missing = []
    out, pos = [], 0
    while True:
        i = text.find("{{", pos)
        if i < 0:
            out.append(text[pos:])
            break
        j = text.find("}}", i)
        name = text[i + 2:j].strip()
        out.append(text[pos:i])
        if name in values:
            out.append(values[name])
        else:
            missing.append(name)
            out.append("??" + name + "??")
        pos = j + 2
    if missing:
        sys.exit("make_report.py: no value for " + ", ".join(missing) + " (is the data complete?)")
    header = ("<!-- generated by scripts/make_report.py from docs/convergence.md.in and docs/data/*.dat; "
              "edit those, not this file -->\n")
    return header + "".join(out), values


def main():
    args = sys.argv[1:]
    if any(a in ("-h", "--help") for a in args):
        print(__doc__.strip())
        return 0
    if len(args) > 1 or (args and args[0] not in ("--check", "--list")):
        print(f"make_report.py: error: unknown arguments {' '.join(args)!r} (allowed: --check, --list, --help)",
              file=sys.stderr)
        return 2
    text, values = render()
    path = os.path.join(REPO, "docs", "convergence.md")
    if "--list" in sys.argv:
        for k in sorted(values):
            if not k.startswith("TABLE"):
                print(k, values[k])
        return 0
    if "--check" in sys.argv:
        with open(path) as f:
            current = f.read()
        if current != text:
            print("docs/convergence.md differs from what scripts/make_report.py makes of the template and data")
            return 1
        print("docs/convergence.md is up to date with docs/data")
        return 0
    with open(path + ".tmp", "w") as f:
        f.write(text)
    os.replace(path + ".tmp", path)
    print(f"make_report.py: wrote {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
