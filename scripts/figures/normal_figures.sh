#!/usr/bin/env bash
# Figures of docs/normal.md (gnuplot), into OUT (default build/figures):
#   OUT/normal_hertz_convergence.png   errors against Hertz vs cells across (Rx/Ry = 1 and 10)
#   OUT/normal_wheel_rail.png          pressure of the worn-wheel-on-rail example
#   scripts/figures/normal_figures.sh [--out OUT]     (from any folder; about 10 s)
#   scripts/figures/normal_figures.sh --out docs/figures   to update docs/normal.md's figures
#   scripts/figures/normal_figures.sh --help          this text
source "$(dirname "${BASH_SOURCE[0]}")/../prebuild_lib.sh"
out=$here/build/figures
while (($#)); do
  case $1 in
    --out) [[ $# -ge 2 ]] || { echo "normal_figures.sh: error: --out needs a folder" >&2; exit 2; }; out=$2; shift 2 ;;
    *) echo "normal_figures.sh: error: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done
mkdir -p "$out" && out=$(cd "$out" && pwd)
build_kcreep -j 2 --target kcreep kcreep_hertz_convergence
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$build_dir/kcreep_hertz_convergence" 320 > "$work/hertz.md"
# columns of the table: | ratio | n | it | area | a | b | approach | pmax | ...
awk -F'|' 'NR > 2 { gsub(/ /, ""); r = $2 + 0; if (r == 1 || r == 10) print r, $3, ($5 < 0 ? -$5 : $5), ($8 < 0 ? -$8 : $8), ($9 < 0 ? -$9 : $9) }' \
  "$work/hertz.md" > "$work/hertz.dat"
(cd "$here" && python3 scripts/wheel_rail_gap.py "$work/wheel_rail.gap" >/dev/null)
cat > "$work/wheel_rail.nml" <<NML
&patch shape = 'gap' /
&normal gap_file = 'wheel_rail.gap', normal_force = 80000.0, e1 = 210000.0, nu1 = 0.28, e2 = 210000.0, nu2 = 0.28 /
&output pressure_file = 'wheel_rail.p' /
NML
(cd "$work" && "$build_dir/kcreep" wheel_rail.nml >/dev/null)
gnuplot <<GP
set terminal pngcairo size 900,600 font ",11"
set output "$out/normal_hertz_convergence.png"
set logscale xy
set xlabel "cells across each axis of Hertz's ellipse"
set ylabel "relative error against Hertz"
set key outside right
set grid
plot "< awk '\$1 == 1' $work/hertz.dat" u 2:3 w lp t "area, Rx/Ry = 1", \
     "< awk '\$1 == 1' $work/hertz.dat" u 2:4 w lp t "approach, Rx/Ry = 1", \
     "< awk '\$1 == 1' $work/hertz.dat" u 2:5 w lp t "pmax, Rx/Ry = 1", \
     "< awk '\$1 == 10' $work/hertz.dat" u 2:3 w lp dt 2 t "area, Rx/Ry = 10", \
     "< awk '\$1 == 10' $work/hertz.dat" u 2:4 w lp dt 2 t "approach, Rx/Ry = 10", \
     "< awk '\$1 == 10' $work/hertz.dat" u 2:5 w lp dt 2 t "pmax, Rx/Ry = 10", \
     [10:320] 0.6/x w l lc rgb "gray" t "1/n", [10:320] 0.15/x**2 w l lc rgb "black" t "1/n^2"
set output "$out/normal_wheel_rail.png"
unset logscale
set size ratio -1
set xlabel "x (rolling) [mm]"
set ylabel "y (lateral) [mm]"
set cblabel "pressure [N/mm^2]"
set key off
plot "$work/wheel_rail.p" u 3:4:5 w points pt 5 ps 0.8 lc palette
GP
echo "wrote $out/normal_hertz_convergence.png and $out/normal_wheel_rail.png"
