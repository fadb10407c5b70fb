#!/usr/bin/env python3
"""Write docs/convergence.md from its template and the study data.

    scripts/make_report.py           write docs/convergence.md
    scripts/make_report.py --check   exit 1 if docs/convergence.md is not what
                                     the template and the data give

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
        if m[2] / m[0] != 4:
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


def render():
    values = {}
    tables = {"TABLE_ALPHA": alpha_section(values), "TABLE_N": n_section(values),
              "TABLE_RICHARDSON": richardson_section(values), "TABLE_TIME": time_section(values)}
    values.update(tables)
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
