#!/usr/bin/env bash
# Benchmark of the normal contact solve (Polonsky-Keer CG with FFT, preconditioned): Hertz's
# sphere on n x n grids, force prescribed, tolerance 1e-10. Prints the table
# and writes it into the "Normal contact solve" section of docs/performance.md
# (between the normal-bench markers; the rest of the file is left alone).
#   scripts/bench/bench_normal.sh              sizes 50 .. 1000 (about 1 min on 2 cores)
#   QUICK=1 scripts/bench/bench_normal.sh      sizes up to 200 (checks the script, not the targets)
#   KCREEP_BUILD_DIR=dir                 build somewhere else (default build/)
# Every timing runs under flock /tmp/kcreep-bench.lock (one benchmark at a time).
#   scripts/bench/bench_normal.sh --help       this text (nothing is built or run)
source "$(dirname "${BASH_SOURCE[0]}")/../prebuild_lib.sh"
build_kcreep -j 2 --target kcreep_normal_bench
bench=$build_dir/kcreep_normal_bench
if [[ -n "${QUICK:-}" ]]; then sizes="50 100 200"; else sizes="50 100 200 400 700 1000"; fi
rows=""
t200=""; t1000=""; m1000=""
for n in $sizes; do
  repeats=3; [[ $n -ge 700 ]] && repeats=1
  line=$(flock /tmp/kcreep-bench.lock "$bench" "$n" "$repeats")
  read -r nn cells its prods resid secs mib eapp epmax <<<"$line"
  echo "$line"
  rows+="| $nn x $nn | $cells | $its | $prods | $resid | $secs | $mib | $eapp | $epmax |"$'\n'
  [[ $n == 200 ]] && t200=$secs
  [[ $n == 1000 ]] && { t1000=$secs; m1000=$mib; }
done
threads=${OMP_NUM_THREADS:-$(nproc)}
load=$(cut -d" " -f1-3 /proc/loadavg)
section=$(cat <<MD
<!-- normal-bench:begin -->
## Normal contact solve

\`scripts/bench/bench_normal.sh\` ($(date -u +%Y-%m-%d), $(nproc) cores, FFTW threads: $threads, load average at the end $load (the machine is shared); best of 3 runs below 700 x 700, one run above).
Hertz's sphere, the contact circle across 80 % of the grid, total force prescribed, constrained
conjugate gradient (Polonsky and Keer) with the circulant inverse of the kernel as preconditioner
(Vollebregt 2014) to a complementarity residual of 1e-10. Per iteration one FFT product (zero-padded
2n x 2n real transforms; a second one when the active set changed) and one preconditioner pass
(n x n periodic transforms, not counted under FFT products). Errors against Hertz's closed forms.

| grid | cells | iterations | FFT products | residual | solve [s] | peak memory [MiB] | approach error | pmax error |
|---|---|---|---|---|---|---|---|---|
${rows}
Targets: 200 x 200 under 1 s: **${t200:-not run} s**; 1000 x 1000 under 60 s: **${t1000:-not run} s** (peak memory ${m1000:-?} MiB, about 21 doubles per cell).
<!-- normal-bench:end -->
MD
)
python3 - "$here/docs/performance.md" "$section" <<'PY'
import sys, re
path, section = sys.argv[1], sys.argv[2]
try:
    text = open(path).read()
except FileNotFoundError:
    text = "# kcreep performance\n"
pattern = re.compile(r"<!-- normal-bench:begin -->.*?<!-- normal-bench:end -->", re.S)
if pattern.search(text):
    text = pattern.sub(lambda m: section, text)
else:
    text = text.rstrip("\n") + "\n\n" + section + "\n"
open(path, "w").write(text)
PY
echo "wrote the normal-solve section of docs/performance.md"
