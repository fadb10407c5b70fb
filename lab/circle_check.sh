#!/usr/bin/env bash
# The unit circle at nu = 0.25 on 40 x 40, 60 x 60 and 80 x 80 grids with
# both schemes: C11, C22, C23 against Kalker's table and the wall time
# (median of --repeats runs, default 3) with the chosen solver method.
#   lab/circle_check.sh [--repeats N] [--grids "40 60 80"] [--method auto|dense|iterative]
#   lab/circle_check.sh --help    this text
# KCREEP: the binary (default build/kcreep of this repository).
usage() { awk 'NR > 1 && /^#/ { sub(/^# ?/, ""); print; next } NR > 1 { exit }' "${BASH_SOURCE[0]}"; }
for arg in "$@"; do case $arg in -h | --help) usage; exit 0 ;; --) break ;; esac; done
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
kcreep=${KCREEP:-$here/build/kcreep}
repeats=3
grids="40 60 80"
method=auto
while (($#)); do
  case $1 in
    --repeats | --grids | --method)
      (($# >= 2)) || { echo "circle_check.sh: error: $1 needs a value (see --help)" >&2; exit 2; } ;;&
    --repeats) repeats=$2; shift 2 ;;
    --grids) grids=$2; shift 2 ;;
    --method) method=$2; shift 2 ;;
    *) echo "circle_check.sh: unknown option $1 (allowed: --repeats N, --grids LIST, --method M)" >&2; exit 2 ;;
  esac
done
[[ -x $kcreep ]] || { echo "circle_check.sh: no kcreep at $kcreep (run scripts/setup.sh)" >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
echo "# unit circle, nu = 0.25, method = $method; dCij: against Kalker's table; t_total: median of $repeats"
printf '%-12s %5s %6s %9s %9s %9s %8s %8s %8s %9s\n' scheme grid n C11 C22 C23 'dC11%' 'dC22%' 'dC23%' 't_total_s'
for scheme in collocation backward; do
  for m in $grids; do
    point=""   # the collocation point belongs to the collocation scheme only
    [[ $scheme == collocation ]] && point=", alpha=0.5"
    cat > "$work/c.nml" <<EON
&patch shape='ellipse', semi_a=1, semi_b=1, mx=$m, my=$m /
&material g=1, nu=0.25 /
&solver scheme='$scheme'$point, method='$method', target_error=0 /
EON
    times=()
    for ((r = 0; r < repeats; r++)); do
      (cd "$work" && "$kcreep" c.nml >/dev/null)
      times+=("$(awk '!/^#/ {print $28}' "$work/c.tab")")
    done
    median=$(printf '%s\n' "${times[@]}" | sort -g | awk '{v[NR]=$1} END {print (NR%2) ? v[(NR+1)/2] : (v[NR/2]+v[NR/2+1])/2}')
    awk -v s=$scheme -v m=$m -v t="$median" '!/^#/ {printf "%-12s %5s %6d %9.4f %9.4f %9.4f %+8.2f %+8.2f %+8.2f %9.3f\n",
        s, m "x" m, $5, $19, $20, $21, 100*($19/$22-1), 100*($20/$23-1), 100*($21/$24-1), t}' "$work/c.tab"
  done
done
