#!/usr/bin/env bash
# Shared pieces of the study scripts sweep_alpha.sh, sweep_n.sh and
# error_vs_time.sh; they source it, it is not run on its own.
#   in a study script:  source "$(dirname "$0")/study_lib.sh"
#   scripts/convergence/study_lib.sh --help                this text
# Provides study_usage, study_die, study_option, study_refs, study_refs_awk,
# study_out_dir, study_grids, study_to_docs, ellipse_nml, square_grid, columns
# and have_gnuplot, and exports KCREEP (default: build/kcreep of this repository).

if [[ ${BASH_SOURCE[0]} == "$0" ]]; then
  case ${1:-} in
    -h | --help) awk 'NR > 1 && /^#/ { sub(/^# ?/, ""); print; next } NR > 1 { exit }' "$0"; exit 0 ;;
    *) echo "study_lib.sh: error: sourced by the study scripts, not run (see --help)" >&2; exit 2 ;;
  esac
fi

study_here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
study_repo=$(cd "$study_here/../.." && pwd)
export KCREEP=${KCREEP:-$study_repo/build/kcreep}

# study_usage: the comment block at the top of the running script
study_usage() { awk 'NR > 1 && /^#/ { sub(/^# ?/, ""); print; next } NR > 1 { exit }' "$0"; }

study_die() { echo "$(basename "$0"): error: $*" >&2; exit 2; }

# study_option ARG...: the options of the sweeps (sweep_alpha.sh, sweep_n.sh)
# that are the same in each: --nu, --out, --jobs, --slurm, --docs and --help
# set nu, out, jobs, slurm, docs; anything else is an unknown option. Sets
# study_used to the number of arguments taken (shift "$study_used").
study_option() {
  study_used=2
  case $1 in
    --nu) nu=$2 ;;
    --out) out=$2 ;;
    --jobs) jobs=(--jobs "$2") ;;
    --slurm) read -r -a slurm <<<"--slurm $2" ;;
    --docs) docs=1; study_used=1 ;;
    -h | --help) study_usage; exit 0 ;;
    *) study_die "unknown option '$1' (see --help)" ;;
  esac
}

# study_refs NU RATIO... -> "ratio c11 u11 c22 u22 c23 u23;" per ratio: the
# refined Kalker table's values and uncertainties (refined_reference.py)
study_refs() {
  local nu=$1 r ref refs=""
  shift
  for r in "$@"; do
    ref=$(python3 "$study_here/refined_reference.py" "$r" "$nu") || study_die "no reference for a/b = $r, nu = $nu"
    refs+="$r $ref;"
  done
  echo "$refs"
}

# study_refs_awk: an awk BEGIN block that maps the ratio to its reference
# values ref11[r], ref22[r], ref23[r]; the awk run gets -v refs="$(study_refs ...)"
study_refs_awk='BEGIN { n = split(refs, rr, ";"); for (i = 1; i <= n; i++) if (split(rr[i], w, " ") == 7)
         { ref11[w[1]] = w[2]; ref22[w[1]] = w[4]; ref23[w[1]] = w[6] } }'

# study_out_dir DIR -> the absolute path of DIR, made if missing
study_out_dir() {
  mkdir -p "$1" || study_die "cannot create '$1'"
  (cd "$1" && pwd)
}

# study_grids M RATIO SQUARE -> "paper:M:M", and " square:MX:MY" after it (about
# M*M near-square cells, square_grid) when SQUARE is 1 and RATIO is not 1
study_grids() {
  local m=$1 r=$2 square=$3 grids="paper:$1:$1" smx smy
  if ((square)) && [[ $(awk -v r="$r" 'BEGIN { print (r != 1) }') == 1 ]]; then
    read -r smx smy < <(square_grid "$m" "$r")
    grids+=" square:$smx:$smy"
  fi
  echo "$grids"
}

# study_to_docs TABLE NAME PLOT...: the plots into docs/figures/ and TABLE as
# docs/data/NAME.dat
study_to_docs() {
  local table=$1 name=$2
  shift 2
  mkdir -p "$study_repo/docs/figures" "$study_repo/docs/data"
  cp "$@" "$study_repo/docs/figures/"
  cp "$table" "$study_repo/docs/data/$name.dat"
}

# ellipse_nml FILE RATIO MX MY NU SCHEME ALPHA [SPIN_SHIFT]
# An ellipse with a/b = RATIO and c = sqrt(a b) = 1 (so f = C).
ellipse_nml() {
  local file=$1 ratio=$2 mx=$3 my=$4 nu=$5 scheme=$6 alpha=$7 shift=${8:-0}
  local a b
  a=$(awk -v r="$ratio" 'BEGIN { printf "%.15g", sqrt(r) }')
  b=$(awk -v r="$ratio" 'BEGIN { printf "%.15g", 1 / sqrt(r) }')
  mkdir -p "$(dirname "$file")"
  local solver="scheme = '$scheme'"
  if [[ $scheme == collocation ]]; then solver+=", alpha = $alpha"; else solver+=", spin_shift = $shift"; fi
  cat >"$file.new" <<EOF
&patch shape = 'ellipse', semi_a = $a, semi_b = $b, mx = $mx, my = $my /
&material nu = $nu /
&solver target_error=0, $solver /
EOF
  # keep the old file when nothing changed (run_cases.sh skips a case whose inputs are unchanged)
  if [[ -f $file ]] && cmp -s "$file" "$file.new"; then rm -f "$file.new"; else mv "$file.new" "$file"; fi
}

# square_grid N RATIO -> "mx my": about N*N grid cells, cells as square as possible
square_grid() {
  awk -v n="$1" -v r="$2" 'BEGIN { mx = int(n * sqrt(r) + 0.5); my = int(n / sqrt(r) + 0.5);
    if (mx < 1) mx = 1; if (my < 1) my = 1; print mx, my }'
}

# columns TABLE NAME... : the named columns of a kcreep table, blank-separated
columns() {
  local table=$1; shift
  awk -v want="$*" '
    /^#/ { header = $0; next }
    { if (!mapped) { n = split(substr(header, 2), h, " "); for (i = 1; i <= n; i++) col[h[i]] = i;
                     m = split(want, w, " "); for (j = 1; j <= m; j++) if (!(w[j] in col)) {
                       print "columns: no column " w[j] > "/dev/stderr"; exit 2 }
                     mapped = 1 }
      line = ""; for (j = 1; j <= m; j++) line = line (j > 1 ? " " : "") $(col[w[j]]); print line }' "$table"
}

have_gnuplot() {
  if command -v gnuplot >/dev/null; then return 0; fi
  echo "$(basename "$0"): gnuplot not found: tables written, plots skipped (scripts/setup.sh installs gnuplot-nox)" >&2
  return 1
}
