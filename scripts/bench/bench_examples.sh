#!/usr/bin/env bash
# Every shipped example (input/*.nml) at its defaults on one thread: the
# median wall time of R runs, the verdict (the wheel/rail table: ok rows of
# all rows), and the median over the examples. CONTACT's sample
# (contact_circle) needs ../shared beside the repository and is left out
# without it.
#   scripts/bench/bench_examples.sh [--repeats R] [NAME ...]   (NAME: input/NAME.nml)
#   scripts/bench/bench_examples.sh --help
set -euo pipefail
usage() { sed -n '2,8p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'; }
repeats=3
names=()
while (($#)); do
  case $1 in
    -h | --help) usage; exit 0 ;;
    --repeats) repeats=${2:?--repeats needs a number}; shift 2 ;;
    -*) echo "bench_examples.sh: unknown option '$1' (see --help)" >&2; exit 2 ;;
    *) names+=("$1"); shift ;;
  esac
done
[[ $repeats =~ ^[1-9][0-9]*$ ]] || { echo "bench_examples.sh: --repeats '$repeats' (allowed: a whole number >= 1)" >&2; exit 2; }
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
build_dir=${KCREEP_BUILD_DIR:-$here/build}
cmake -S "$here" -B "$build_dir" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build_dir" -j "$(nproc)" >/dev/null
if ((${#names[@]} == 0)); then
  for f in "$here"/input/*.nml; do names+=("$(basename "$f" .nml)"); done
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export OMP_NUM_THREADS=1
printf '| example | verdict | median wall s (%s runs, one thread) |\n|---|---|---|\n' "$repeats"
all=()
for name in "${names[@]}"; do
  input=$here/input/$name.nml
  [[ -f $input ]] || { echo "bench_examples.sh: no input/$name.nml" >&2; exit 2; }
  if grep -q "contact_inp" "$input" && [[ ! -d $here/../shared/contact-samples ]]; then continue; fi
  times=()
  for ((r = 0; r < repeats; r++)); do
    start=$(date +%s.%N)
    # one benchmark at a time on a shared machine; the run's tables land in $work
    (cd "$work" && flock /tmp/kcreep-bench.lock "$build_dir/kcreep" "$input" >"$work/out" 2>&1) ||
      { echo "bench_examples.sh: input/$name.nml failed: $(tail -1 "$work/out")" >&2; exit 1; }
    times+=("$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN {print b - a}')")
  done
  median=$(printf '%s\n' "${times[@]}" | sort -g | awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}')
  if grep -q "wheel/rail:" "$work/out"; then
    verdict="$(grep -cE ' ok$' "$work/out") of $(grep -cE ' (ok|uncertain)$' "$work/out") rows ok"
  else
    verdict=$(awk '$1 == "verdict:" {print $2; exit}' "$work/out")
  fi
  all+=("$median")
  printf '| %s | %s | %.2f |\n' "$name" "$verdict" "$median"
done
printf '\nmedian over %d examples: %.2f s\n' "${#all[@]}" \
  "$(printf '%s\n' "${all[@]}" | sort -g | awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}')"
