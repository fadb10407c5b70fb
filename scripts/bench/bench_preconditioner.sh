#!/usr/bin/env bash
# Benchmark of the two GMRES preconditioners, side by side in one run: the
# strip preconditioner (exact inverse of each grid row's own block) and the
# circulant one (running sum along the rows from the leading edge and the FFT
# inverse of the displacement operator). One grid each, given as is
# (target_error = 0, no error estimate), method 'iterative', backward scheme,
# nu = 0.25, three load cases. Median wall time of the kcreep process over
# the repeats; iterations and the solve phase from kcreep's summary. Writes
# the table into the "precond" section of docs/performance.md.
#   scripts/bench/bench_preconditioner.sh            all cases, 3 repeats (about 3 min on 2 cores)
#   QUICK=1 scripts/bench/bench_preconditioner.sh    the small cases, 1 repeat (checks the script)
#   KCREEP_BUILD_DIR=dir                       build somewhere else (default build/)
# Every timing runs under flock /tmp/kcreep-bench.lock (one benchmark at a time).
#   scripts/bench/bench_preconditioner.sh --help     this text (nothing is built or run)
source "$(dirname "${BASH_SOURCE[0]}")/../prebuild_lib.sh"
build_kcreep -j 2 --target kcreep
kcreep=$build_dir/kcreep
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# label | &patch contents
cases=(
  "circle 48 x 48|shape='ellipse', semi_a=1, semi_b=1, mx=48, my=48"
  "circle 96 x 96|shape='ellipse', semi_a=1, semi_b=1, mx=96, my=96"
  "circle 192 x 192|shape='ellipse', semi_a=1, semi_b=1, mx=192, my=192"
  "a/b = 10, 480 x 48|shape='ellipse', semi_a=3.16227766, semi_b=0.316227766, mx=480, my=48"
  "a/b = 0.1, 48 x 480|shape='ellipse', semi_a=0.316227766, semi_b=3.16227766, mx=48, my=480"
  "circle 384 x 384|shape='ellipse', semi_a=1, semi_b=1, mx=384, my=384"
  "a/b = 10, 960 x 96|shape='ellipse', semi_a=3.16227766, semi_b=0.316227766, mx=960, my=96"
)
repeats=3
if [[ -n "${QUICK:-}" ]]; then cases=("${cases[@]:0:2}"); repeats=1; fi

# one run: prints "iterations solve_seconds wall_seconds"
run_one() {
  local nml=$1 out
  out=$(flock /tmp/kcreep-bench.lock /usr/bin/time -f 'wall %e' "$kcreep" "$nml" 2>&1)
  awk '/GMRES/ { for (i = 1; i <= NF; i++) if ($i ~ /^iterations/) it = $(i - 1) }
       /time assemble factor solve total/ { solve = $(NF - 1) }
       /^wall/ { wall = $2 }
       END { print it, solve, wall }' <<<"$out"
}

rows=""
for entry in "${cases[@]}"; do
  label=${entry%%|*}
  patch=${entry#*|}
  row="| $label |"
  declare -A wall_of=()
  for pc in strip circulant; do
    nml=$work/${pc}.nml
    printf "&patch %s /\n&material nu = 0.25 /\n&solver target_error = 0, method = 'iterative', preconditioner = '%s' /\n&output table_file = '%s' /\n" \
      "$patch" "$pc" "$work/out.tab" >"$nml"
    its=""; solves=""; walls=""
    for ((r = 0; r < repeats; r++)); do
      read -r it solve wall < <(run_one "$nml")
      its=$it; solves+="$solve"$'\n'; walls+="$wall"$'\n'
    done
    s=$(median <<<"${solves%$'\n'}"); w=$(median <<<"${walls%$'\n'}")
    wall_of[$pc]=$w
    row+=" $its | $s | $w |"
    echo "$label  $pc: $its iterations, solve $s s, process $w s" >&2
  done
  ratio=$(awk -v a="${wall_of[strip]}" -v b="${wall_of[circulant]}" 'BEGIN { printf "%.2f", a / b }')
  rows+="$row ${ratio}x |"$'\n'
  unset wall_of
done

load=$(cut -d" " -f1-3 /proc/loadavg)
section=$(cat <<MD
<!-- precond:begin -->
## GMRES preconditioners

\`scripts/bench/bench_preconditioner.sh\` ($(date -u +%Y-%m-%d), $(nproc) cores, load average at the end $load; median of $repeats runs).
One grid as given (\`target_error = 0\`), \`method = 'iterative'\`, backward scheme, nu = 0.25, the three
load cases in lockstep, tolerance 1e-11. *strip*: the exact inverse of each grid row's own block
(the preconditioner before); *circulant*: the running sum along each row from the leading edge (the
exact inverse of the one-cell upwind difference) followed by the FFT inverse of the displacement
operator on the padded periodic grid (the default). Solve: GMRES phase; process: the whole kcreep run.

| patch, grid | strip iterations | strip solve [s] | strip process [s] | circulant iterations | circulant solve [s] | circulant process [s] | speed-up (process) |
|---|---|---|---|---|---|---|---|
${rows}
<!-- precond:end -->
MD
)
python3 - "$here/docs/performance.md" "$section" <<'PY'
import sys, re
path, section = sys.argv[1], sys.argv[2]
text = open(path).read()
pattern = re.compile(r"<!-- precond:begin -->.*?<!-- precond:end -->", re.S)
if pattern.search(text):
    text = pattern.sub(lambda m: section, text)
else:
    text = text.rstrip("\n") + "\n\n" + section + "\n"
open(path, "w").write(text)
PY
echo "$section"
