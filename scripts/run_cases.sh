#!/usr/bin/env bash
# Run kcreep on a list of cases and merge their tables.
#
#   scripts/run_cases.sh [--jobs N] LIST OUT_TABLE
#   scripts/run_cases.sh --slurm [options for the SLURM back-end] LIST OUT_TABLE
#   scripts/run_cases.sh --help
#
# LIST: one namelist path per line (blank lines and '#' lines skipped;
# relative paths are relative to LIST's folder). Each case runs in its own
# folder, so its default table <name>.tab lands next to the namelist (for a
# contact table, a case with &wheel_rail: <name>.wr; one merged table holds
# one kind, so a list that mixes them is refused; the &output table_file
# and wheel_rail_file of a case are not followed: use the defaults).
# Cases run in parallel, N at a time (default: the number of cores; each
# kcreep gets one BLAS thread then). A case is skipped when its .tab exists
# and its input fingerprint has not changed since that table was made
# (`kcreep --fingerprint`, the one rule of kcreep --batch and the SLURM
# route: a SHA-256 of the program, the namelist and every file it reads,
# by content; kept in <name>.tab.stamp). So running again resumes an
# interrupted study and reruns exactly the cases whose inputs changed.
# A failed case is reported and the others go on; the summary counts them.
# Finally all rows are merged into OUT_TABLE (header of the first table,
# rows in LIST order, each named as kcreep --batch names it: the case's
# path in LIST without the extension, e.g. a/case; contact tables as
# kcreep --batch merges them: each row led by its case's name, each case's
# description in '# case K' comments). Exit status: 0 all done, 1 some cases
# failed, 2 bad usage.
#
# Environment: KCREEP (the binary; default build/kcreep of this repository).
# --slurm hands the same job to scripts/slurm/run_cases_slurm.sh.
set -uo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
repo=$(cd "$here/.." && pwd)

usage() { awk 'NR > 1 && /^#/ { sub(/^# ?/, ""); print; next } NR > 1 { exit }' "${BASH_SOURCE[0]}"; }
die() { echo "run_cases: error: $*" >&2; exit 2; }

jobs=$(nproc 2>/dev/null || echo 1)
if [[ ${1:-} == --slurm ]]; then
  shift
  backend=$here/slurm/run_cases_slurm.sh
  [[ -x $backend ]] || die "--slurm: the SLURM back-end $backend is not there (or not executable)"
  (($# >= 2)) || die "--slurm needs LIST OUT_TABLE as its last two arguments"
  list=${*: -2:1}
  out=${*: -1:1}
  exec "$backend" "$list" "$out" "${@:1:$#-2}"
fi
while (($#)); do
  case $1 in
    -j | --jobs) [[ ${2:-} =~ ^[1-9][0-9]*$ ]] || die "--jobs needs a positive integer (got '${2:-}')"; jobs=$2; shift 2 ;;
    -h | --help) usage; exit 0 ;;
    --slurm) die "--slurm must come first: run_cases.sh --slurm [options] LIST OUT_TABLE" ;;
    -*) die "unknown option '$1' (see --help)" ;;
    *) break ;;
  esac
done
(($# == 2)) || { usage >&2; exit 2; }
list=$1
out=$2
[[ -r $list ]] || die "case list '$list' cannot be read"
kcreep=${KCREEP:-$repo/build/kcreep}
[[ -x $kcreep ]] || die "kcreep binary '$kcreep' not found: build it (scripts/setup.sh) or set KCREEP"
out_dir=$(dirname "$out")
[[ -d $out_dir && -w $out_dir ]] || die "output folder '$out_dir' does not exist or is not writable"

list_dir=$(cd "$(dirname "$list")" && pwd)
# A case's name in the merged table, the rule of kcreep --batch: its path as
# the list gives it, relative to the list's folder, without './' and the
# extension, blanks as '_' (a/case.nml and b/case.nml stay a/case and b/case).
listed_name() {
  local name=$1 base
  [[ $name == "$list_dir"/* ]] && name=${name#"$list_dir"/}
  while [[ $name == ./* && ${#name} -gt 2 ]]; do name=${name#./}; done
  base=${name##*/}
  [[ $base == ?*.* ]] && name=${name%.*}
  name=${name//[[:space:]]/_}
  echo "${name:--}"
}
cases=() names=()
while IFS= read -r line || [[ -n $line ]]; do
  line=${line%%#*}
  line=$(echo "$line" | xargs)
  [[ -z $line ]] && continue
  names+=("$(listed_name "$line")")
  [[ $line == /* ]] || line=$list_dir/$line
  cases+=("$line")
done <"$list"
n=${#cases[@]}
((n > 0)) || die "case list '$list' names no cases"
# A contact table: the namelist has a &wheel_rail group (outside '!' comments).
is_table() { [[ -r $1 ]] && sed 's/!.*//' "$1" | grep -qiE '(^|[^[:alnum:]_])&wheel_rail([^[:alnum:]_]|$)'; }
kinds=() first_table= first_patch=
for ((k = 0; k < n; k++)); do
  if is_table "${cases[k]}"; then kinds+=(wr); first_table=${first_table:-${cases[k]}}
  else kinds+=(tab); [[ -r ${cases[k]} ]] && first_patch=${first_patch:-${cases[k]}}; fi
done
[[ -n $first_table && -n $first_patch ]] &&
  die "case list '$list': '$first_table' is a contact table (&wheel_rail) and '$first_patch' a single patch: one merged table holds one kind (give each kind its own list)"
# what each case reads, fingerprinted (one line per case, in list order)
mapfile -t stamps < <(printf '%s\n' "${cases[@]}" | xargs -d '\n' "$kcreep" --fingerprint | cut -d' ' -f1)
((${#stamps[@]} == n)) || die "could not fingerprint the inputs of the cases (kcreep --fingerprint failed)"

# One BLAS thread per case when several cases share the cores.
if ((jobs > 1)); then
  export OPENBLAS_NUM_THREADS=${OPENBLAS_NUM_THREADS:-1} OMP_NUM_THREADS=${OMP_NUM_THREADS:-1}
fi

state=$(mktemp -d "${TMPDIR:-/tmp}/run_cases.XXXXXX")
trap 'rm -rf "$state"' EXIT
interrupted() {  # stop the running cases (their kcreep children by id), keep what is done
  local job child
  for job in $(jobs -p); do
    for child in $(pgrep -P "$job" 2>/dev/null); do kill "$child" 2>/dev/null; done
    kill "$job" 2>/dev/null
  done
  echo "run_cases: interrupted; run again to resume (finished points are kept)" >&2
  exit 130
}
trap interrupted INT TERM HUP

table_of() {  # the case's own table (the default name a single run writes in the namelist's folder)
  local nml=$1 k
  for ((k = 0; k < n; k++)); do
    [[ ${cases[k]} == "$nml" && ${kinds[k]} == wr ]] && { echo "${nml%.*}.wr"; return; }
  done
  echo "${nml%.*}.tab"
}
stamp_of() { echo "$(table_of "$1").stamp"; }

run_one() {  # k nml: run in the namelist's folder, leave k.rc and k.err in $state
  local k=$1 nml=$2 dir base rc stamp
  dir=$(dirname "$nml")
  base=$(basename "$nml")
  stamp=$(stamp_of "$nml")
  # no fingerprint while the case runs: a table left by a killed run is not trusted
  rm -f "$stamp"
  # runs in its own background subshell: cd is local, kcreep is its direct child
  cd "$dir" && "$kcreep" "$base" >"${base%.*}.log" 2>"$state/$k.err"
  rc=$?
  # the fingerprint of the inputs as they were when the case started
  if ((rc == 0)); then echo "${stamps[k]}" >"$stamp.tmp" && mv "$stamp.tmp" "$stamp"; fi
  echo "$rc" >"$state/$k.rc"
}

start=$(date +%s)
finished=0 skipped=0 failed=0 running=0
progress() {
  local now elapsed remaining ran
  now=$(date +%s)
  elapsed=$((now - start))
  ran=$((finished - skipped))
  if ((ran > 0)); then
    remaining=$(((elapsed * (n - finished) + ran - 1) / ran))
  else
    remaining='?'
  fi
  printf 'run_cases: point %d of %d, elapsed %ds, estimated remaining %ss\n' "$finished" "$n" "$elapsed" "$remaining"
}
collect() {  # account for every case that has finished since the last call
  local k rc
  for ((k = 0; k < n; k++)); do
    [[ -e $state/$k.rc && ! -e $state/$k.seen ]] || continue
    touch "$state/$k.seen"
    rc=$(<"$state/$k.rc")
    finished=$((finished + 1))
    running=$((running - 1))
    if [[ $rc != 0 ]]; then
      failed=$((failed + 1))
      echo "run_cases: FAILED (exit $rc): ${cases[k]}: $(tail -n 1 "$state/$k.err" 2>/dev/null)" >&2
    fi
    progress
  done
}

for ((k = 0; k < n; k++)); do
  nml=${cases[k]}
  if [[ ! -r $nml ]]; then
    echo "run_cases: FAILED: ${nml}: namelist not found" >&2
    echo 2 >"$state/$k.rc"; touch "$state/$k.seen"
    finished=$((finished + 1)); failed=$((failed + 1))
    continue
  fi
  tab=$(table_of "$nml")
  stamp=$(stamp_of "$nml")
  if [[ -s $tab && -f $stamp && $(<"$stamp") == "${stamps[k]}" ]]; then
    echo 0 >"$state/$k.rc"; touch "$state/$k.seen"
    finished=$((finished + 1)); skipped=$((skipped + 1))
    continue
  fi
  while ((running >= jobs)); do
    wait -n 2>/dev/null
    collect
  done
  run_one "$k" "$nml" &
  running=$((running + 1))
done
while ((running > 0)); do
  wait -n 2>/dev/null || true
  collect
  if ((running > 0)) && ! jobs -r | grep -q .; then collect; break; fi
done
wait

# Merge: the header of the first table, then the rows in list order.
tmp_out=$out.run_cases-tmp.$$
header_done=0 merged=0 rows=0
merge_patches() {
  for ((k = 0; k < n; k++)); do
    [[ $(<"$state/$k.rc") == 0 ]] || continue
    tab=$(table_of "${cases[k]}")
    [[ -r $tab ]] || continue
    if ((header_done == 0)); then
      grep '^#' "$tab" | grep -v '^# WARNING'
      header_done=1
    fi
    # the row named by the list, as --batch names it (the table says only its file name)
    grep -v '^#' "$tab" | awk -v name="${names[k]}" '{ i = index($0, " "); print name substr($0, i) }'
    merged=$((merged + 1)) rows=$((rows + $(grep -vc '^#' "$tab")))
  done
}
merge_tables() {  # as kcreep --batch: each case's description, the column notes, then its rows led by its name
  local first=
  for ((k = 0; k < n; k++)); do
    [[ $(<"$state/$k.rc") == 0 && -r $(table_of "${cases[k]}") ]] || continue
    tab=$(table_of "${cases[k]}")
    first=${first:-$tab}
    awk -v lead="# case $((k + 1)) '${names[k]}': " 'NR > 5 { exit } { sub(/^# /, ""); print lead $0 }' "$tab"
  done
  [[ -n $first ]] || return 0
  sed -n '6,7p' "$first"
  sed -n '8s/^# /# case /p' "$first"
  header_done=1
  for ((k = 0; k < n; k++)); do
    [[ $(<"$state/$k.rc") == 0 && -r $(table_of "${cases[k]}") ]] || continue
    tab=$(table_of "${cases[k]}")
    grep -v '^#' "$tab" | awk -v name="${names[k]}" '{ print name " " $0 }'
    merged=$((merged + 1)) rows=$((rows + $(grep -vc '^#' "$tab")))
  done
}
if [[ -n $first_table ]]; then merge_tables >"$tmp_out"; else merge_patches >"$tmp_out"; fi
if ((header_done)); then
  mv "$tmp_out" "$out"
else
  rm -f "$tmp_out"
fi
elapsed=$(($(date +%s) - start))
echo "run_cases: done: $n points, $((n - failed)) ok ($skipped already done), $failed failed, ${elapsed}s; table $out ($rows rows of $merged cases)"
((failed == 0))
