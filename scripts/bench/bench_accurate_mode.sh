#!/usr/bin/env bash
# The accurate mode (&solver target_error = 1e-4) of two kcreep builds side by
# side in one run: ellipses with c = sqrt(ab) = 1, nu = NU (0.25), only semi_a,
# semi_b given, over a/b = 0.1 ... 10, always solved (method = 'iterative':
# the default 'auto' answers the table's fine rows from the table, nothing to
# time; set METHOD=auto to time that). For each a/b: the median process wall
# time of each build over the repeats (the builds alternate), their ratio, the
# finest grid and the verdict of each. Both builds get the same cell budget
# when CELL_BUDGET is set (to compare the speed of the levels); otherwise
# each runs its own default.
#   scripts/bench/bench_accurate_mode.sh OLD_KCREEP [NEW_KCREEP]   (NEW: build/kcreep)
#   REPEATS=3 RATIOS=0.1,0.25,0.5,1,2,4,10 NU=0.25 METHOD=iterative CELL_BUDGET=1.6e5  the defaults but for CELL_BUDGET (unset)
# Every timing runs under flock /tmp/kcreep-bench.lock (one benchmark at a time).
#   scripts/bench/bench_accurate_mode.sh --help     this text (nothing is run)
#   KCREEP_BUILD_DIR=dir                       NEW_KCREEP's default folder (default build/)
source "$(dirname "${BASH_SOURCE[0]}")/../prebuild_lib.sh"   # --help, set -euo pipefail, build_dir, median
if (($# < 1)); then
  echo "bench_accurate_mode.sh: error: give the kcreep binary to compare with (OLD_KCREEP)" >&2
  exit 2
fi
old=$(realpath "$1")
new=$(realpath "${2:-$build_dir/kcreep}")
for exe in "$old" "$new"; do
  [[ -x $exe ]] || { echo "bench_accurate_mode.sh: error: $exe is not an executable kcreep" >&2; exit 2; }
done
repeats=${REPEATS:-3}
IFS=, read -r -a ratios <<< "${RATIOS:-0.1,0.25,0.5,1,2,4,10}"
nu=${NU:-0.25}
method=${METHOD:-iterative}
budget=${CELL_BUDGET:+, cell_budget = $CELL_BUDGET}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# one run: "wall finest_grid verdict"
run_one() {
  local exe=$1 out
  out=$(cd "$work" && flock /tmp/kcreep-bench.lock /usr/bin/time -f 'wall %e' "$exe" case.nml 2>&1)
  awk '/^wall/ { w = $2 } /^  verdict:/ { v = $2 }
       /^  patch:/ { if (match($0, /grid [0-9]+ x [0-9]+/)) { split(substr($0, RSTART, RLENGTH), p, " "); g = p[2] "x" p[4] } }
       END { printf "%s %s %s\n", w, g, v }' <<< "$out"
}

echo "accurate mode, target_error = 1e-4, method = $method${budget:+ (cell_budget = $CELL_BUDGET)}, nu = $nu, median of $repeats"
echo "old: $old"
echo "new: $new"
printf '%-6s %9s %9s %7s  %-12s %-10s %-12s %-10s\n' "a/b" "old [s]" "new [s]" "old/new" "old grid" "old" "new grid" "new"
for r in "${ratios[@]}"; do
  read -r a b < <(awk -v r="$r" 'BEGIN { printf "%.15g %.15g\n", sqrt(r), 1 / sqrt(r) }')
  printf "&patch shape = 'ellipse', semi_a = %s, semi_b = %s /\n&material nu = %s /\n&solver target_error = 1e-4, method = '%s'%s /\n&output table_file = 'case.tab' /\n" \
    "$a" "$b" "$nu" "$method" "$budget" > "$work/case.nml"
  : > "$work/old" ; : > "$work/new"
  for ((k = 0; k < repeats; k++)); do
    run_one "$old" >> "$work/old"
    run_one "$new" >> "$work/new"
  done
  t_old=$(cut -d' ' -f1 "$work/old" | median)
  t_new=$(cut -d' ' -f1 "$work/new" | median)
  read -r _ g_old v_old < "$work/old"
  read -r _ g_new v_new < "$work/new"
  printf '%-6s %9.2f %9.2f %7.2f  %-12s %-10s %-12s %-10s\n' "$r" "$t_old" "$t_new" \
    "$(awk -v a="$t_old" -v b="$t_new" 'BEGIN { print a / b }')" "$g_old" "$v_old" "$g_new" "$v_new"
done
