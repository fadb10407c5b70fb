#!/usr/bin/env python3
"""Error and run time of kcreep's default run over Kalker's grid of a/b and nu.

    accuracy_table.py [--solver "target_error = 1e-4"] [--ratios 0.5,1,2] [--kalker] [--nu 0,0.25,0.5]
                      [--reference docs/data/kalker_refined.dat] [--out FILE]
    accuracy_table.py --random N [--solver ...] [--out FILE]

Each point is the ellipse c = sqrt(ab) = 1 with only semi_a, semi_b and nu
given (plus --solver settings): kcreep chooses the grids. The error is
against the refined table (tools/maintenance/refine_kalker_table.sh), whose own
uncertainty u is printed beside it; "bounded" counts the points where
kcreep's estimate err covered the measured error |c - ref| (a point whose
measured error is within the reference's u of the estimate counts as
bounded-within-u). Time: the process wall time, and its CPU time (user +
system), which a shared machine's load distorts less. --kalker: only
Kalker's 19 a/b (the refined table has rows between them too).

--random N: N ellipses spread over a/b in [0.1, 10] (log-uniform) and nu in
[0, 0.5] by the golden-ratio sequences of build/kcreep_table_bench; per
ellipse whether kcreep answered from the refined table (no cells) or solved,
its verdict and time. No reference there: this measures what a user meets.
"""
import argparse
import math
import os
import resource
import statistics
import sys

sys.path[:0] = [os.path.join(os.path.dirname(os.path.abspath(__file__)), d) for d in (".", "../tools/maintenance", "../scripts/convergence", "../tests/calibration")]
import kcreep_levels as K  # noqa: E402

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")


def read_reference(path):
    ref = {}
    rows = K.read_table(path)
    for r in rows:
        key = (float(r["a_over_b"]), float(r["nu"]))
        ref[key] = {c: (float(r[c]), float(r["u" + c[1:]])) for c in ("c11", "c22", "c23")}
    return ref


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--solver", default="")
    ap.add_argument("--ratios", default="")
    ap.add_argument("--nu", default="0,0.25,0.5")
    ap.add_argument("--reference", default=os.path.join(ROOT, "docs", "data", "kalker_refined.dat"))
    ap.add_argument("--kalker", action="store_true", help="only Kalker's 19 a/b")
    ap.add_argument("--random", type=int, default=0, help="N ellipses spread over the table's range")
    ap.add_argument("--out", default="")
    args = ap.parse_args()
    if args.random:
        return random_run(args)
    ref = read_reference(args.reference)
    if args.kalker:
        g = [round(0.1 * k, 1) for k in range(1, 11)]
        args.ratios = ",".join(f"{x:.6g}" for x in sorted(set(g + [1 / x for x in g])))
    nus = [float(x) for x in args.nu.split(",")]
    ratios = [float(x) for x in args.ratios.split(",")] if args.ratios else None
    keys = sorted(k for k in ref if any(abs(k[1] - x) < 1e-9 for x in nus)
                  and (ratios is None or any(abs(k[0] - x) < 1e-5 * x for x in ratios)))
    lines = ["# a_over_b nu  err11 est11 u11  err22 est22 u22  err23 est23 u23 (relative, %)  mx my  seconds cpu_seconds  verdict"]
    errs = {c: [] for c in ("c11", "c22", "c23")}
    bounded = {c: 0 for c in errs}
    within_u = {c: 0 for c in errs}
    times, cpus, verdicts = [], [], []
    for r, nu in keys:
        a, b = math.sqrt(r), 1 / math.sqrt(r)
        nml = (f"&patch shape = 'ellipse', semi_a = {a!r}, semi_b = {b!r} /\n&material nu = {nu!r} /\n"
               f"&solver {args.solver} /\n&output table_file = 'case.tab' /\n")
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        rows, wall, _ = K.run_kcreep(nml)
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
        row = rows[-1]
        parts = [f"{r:8.4g} {nu:4g}"]
        for c, e in (("c11", "err11"), ("c22", "err22"), ("c23", "err23")):
            v, u = ref[(r, nu)][c]
            err = abs(float(row[c]) - v) / abs(v)
            est = float(row[e])
            errs[c].append(err)
            bounded[c] += est >= err
            within_u[c] += est + u / abs(v) >= err
            parts.append(f"{100 * err:7.3f} {100 * est:7.3f} {100 * u / abs(v):6.3f}")
        times.append(wall)
        cpus.append(cpu)
        verdicts.append(row["verdict"])
        parts.append(f"{row['mx']:>5} {row['my']:>5} {wall:7.2f} {cpu:7.2f}  {row['verdict']}")
        lines.append("  ".join(parts))
        print(lines[-1], flush=True)
    n = len(keys)
    lines.append(f"# {n} points, settings: &solver {args.solver or '(defaults)'} /")
    for c in errs:
        lines.append(f"# {c}: error median {100 * statistics.median(errs[c]):.3f} %, worst {100 * max(errs[c]):.3f} %; "
                     f"estimate bounded the error in {bounded[c]} of {n} ({within_u[c]} allowing the reference's u)")
    lines.append(f"# time: median {statistics.median(times):.2f} s, worst {max(times):.2f} s (process wall); CPU "
                 f"median {statistics.median(cpus):.2f} s, worst {max(cpus):.2f} s; verdict ok in "
                 f"{sum(v == 'ok' for v in verdicts)} of {n}")
    for line in lines[-5:]:
        print(line)
    if args.out:
        with open(args.out, "w") as f:
            f.write("\n".join(lines) + "\n")


def timed_run(nml):
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    rows, wall, _ = K.run_kcreep(nml)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return rows[-1], wall, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def random_run(args):
    lines = ["# a_over_b nu  c11 c22 c23  err11 err22 err23 (relative, %)  answer  mx my  seconds cpu_seconds  verdict"]
    times, cpus, answers, verdicts = [], [], [], []
    for k in range(1, args.random + 1):
        r = 10 ** (2 * ((k * 0.6180339887498949) % 1.0) - 1)
        nu = 0.5 * ((k * 0.7548776662466927) % 1.0)
        a, b = math.sqrt(r), 1 / math.sqrt(r)
        nml = (f"&patch shape = 'ellipse', semi_a = {a!r}, semi_b = {b!r} /\n&material nu = {nu!r} /\n"
               f"&solver {args.solver} /\n&output table_file = 'case.tab' /\n")
        row, wall, cpu = timed_run(nml)
        answer = "table" if int(row["n"]) == 0 else "solved"
        times.append(wall)
        cpus.append(cpu)
        answers.append(answer)
        verdicts.append(row["verdict"])
        lines.append(f"{r:8.4g} {nu:6.4f}  " + " ".join(f"{float(row[c]):.6g}" for c in ("c11", "c22", "c23")) + "  "
                     + " ".join(f"{100 * float(row[e]):.3f}" for e in ("err11", "err22", "err23"))
                     + f"  {answer:6} {row['mx']:>5} {row['my']:>5} {wall:7.3f} {cpu:7.3f}  {row['verdict']}")
        print(lines[-1], flush=True)
    n = len(times)
    solved = [t for t, a in zip(times, answers) if a == "solved"]
    lines.append(f"# {n} ellipses, settings: &solver {args.solver or '(defaults)'} /")
    lines.append(f"# answered from the table: {n - len(solved)} of {n}; verdict ok in "
                 f"{sum(v == 'ok' for v in verdicts)} of {n}")
    lines.append(f"# time: median {statistics.median(times):.3f} s, worst {max(times):.2f} s (process wall); CPU median "
                 f"{statistics.median(cpus):.3f} s, worst {max(cpus):.2f} s"
                 + (f"; the solved ones: median {statistics.median(solved):.2f} s, worst {max(solved):.2f} s"
                    if solved else ""))
    for line in lines[-3:]:
        print(line)
    if args.out:
        with open(args.out, "w") as f:
            f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
