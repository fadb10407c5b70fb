#!/usr/bin/env bash
# Draw the exact rolling curve of a kcreep run beside FASTSIM's, with gnuplot:
#   <CASE>_rolling.png  |F|/(mu Fn) against the size of the creepage |(xi, eta, phi)|
#                       (log axis): the exact solution (&rolling, CASE.roll) and, when
#                       the run had &fastsim at the same creepages (CASE.creep), one
#                       line per FASTSIM flexibility source; the adhesion fraction of
#                       the exact solution on the right axis.
# usage: scripts/plot_rolling.sh CASE.roll [--creep CASE.creep] [--out FOLDER]
# FOLDER defaults to build/output of this checkout (created; never docs/).
# scripts/plot_rolling.sh --help: this text
usage() { awk 'NR > 1 && /^#/ { sub(/^# ?/, ""); print; next } NR > 1 { exit }' "${BASH_SOURCE[0]}"; }
for arg in "$@"; do case $arg in -h | --help) usage; exit 0 ;; --) break ;; esac; done
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
roll=${1:?usage: scripts/plot_rolling.sh CASE.roll [--creep CASE.creep] [--out FOLDER]}
shift
creep=${roll%.roll}.creep
out=$here/build/output
while [[ $# -gt 0 ]]; do
  case $1 in
    --creep) creep=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    *) echo "plot_rolling.sh: unknown option $1" >&2; exit 2 ;;
  esac
done
command -v gnuplot >/dev/null || { echo "plot_rolling.sh: gnuplot not found (scripts/setup.sh installs it)" >&2; exit 2; }
[[ -r $roll ]] || { echo "plot_rolling.sh: cannot read '$roll'" >&2; exit 2; }
mkdir -p "$out"
name=$(basename "${roll%.roll}")
png=$out/${name}_rolling.png
fastsim=''
if [[ -r $creep ]]; then
  for s in $(awk '!/^#/ && NF >= 11 { print $9 }' "$creep" | sort -u); do
    fastsim+=", '$creep' using (sqrt(\$1**2+\$2**2+\$3**2)):(strcol(9) eq '$s' ? sqrt(\$10**2+\$11**2) : 1/0) with linespoints pt 6 title 'FASTSIM, L $s'"
  done
fi
gnuplot <<GP
set terminal pngcairo size 900,600 noenhanced
set output '$png'
set logscale x
set xlabel '|(xi, eta, phi)|'
set ylabel '|F| / (mu Fn)'
set y2label 'adhesion fraction (exact)'
set y2tics
set yrange [0:1.05]
set y2range [0:1.05]
set key left top
set grid
plot '$roll' using (sqrt(\$1**2+\$2**2+\$3**2)):(sqrt(\$9**2+\$10**2)) with linespoints lw 2 pt 7 title 'exact (&rolling)', \
     '$roll' using (sqrt(\$1**2+\$2**2+\$3**2)):8 axes x1y2 with lines dt 2 title 'adhesion (exact)'$fastsim
GP
echo "plot_rolling.sh: $png"
