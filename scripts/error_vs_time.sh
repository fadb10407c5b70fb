#!/usr/bin/env bash
# Error against run time: for each scheme and mesh, the relative error of
# C11, C22, C23 against the best reference available (the Richardson limit
# of both schemes, see below) and the wall time of the run; a table and
# log-log plots (one curve per scheme and coefficient).
#
#   scripts/error_vs_time.sh [options]
#     --ratio 1             ellipse ratio a/b (c = 1)
#     --meshes "10 ... 80"  grid sizes M (M x M cells; near-square cells when
#                           a/b != 1, about M*M cells)
#     --alpha 0.5           collocation point
#     --nu 0.25             Poisson's ratio
#     --repeats 3           runs per point; the median time is reported
#     --out DIR             output folder [./studies/error_vs_time]
#     --jobs N              cases in parallel [1: timings of runs that share
#                           the cores with each other are not worth much]
#     --slurm "OPTS"        run through the SLURM back-end with these options
#     --help                this text
#     --docs                also copy plots and tables into docs/
# Reference: each scheme is Richardson-extrapolated through its three finest
# meshes in ratio 2 (default 20, 40, 80; add 100 or 160 to go further); the reference is the mean of the
# two schemes' limits, and half their difference is its uncertainty (printed).
# Writes DIR/runs.tab (every run), DIR/error_vs_time.dat, DIR/error_vs_time_*.png.
set -uo pipefail
source "$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/study_lib.sh"

ratio=1 meshes="10 15 20 30 40 60 80" alpha=0.5 nu=0.25 repeats=3
out=$PWD/studies/error_vs_time jobs=(--jobs 1) slurm=() docs=0
while (($#)); do
  case $1 in
    --ratio) ratio=$2; shift 2 ;;
    --meshes) meshes=$2; shift 2 ;;
    --alpha) alpha=$2; shift 2 ;;
    --nu) nu=$2; shift 2 ;;
    --repeats) repeats=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    --jobs) jobs=(--jobs "$2"); shift 2 ;;
    --slurm) read -r -a slurm <<<"--slurm $2"; jobs=(); shift 2 ;;
    --docs) docs=1; shift ;;
    -h | --help) study_usage; exit 0 ;;
    *) study_die "unknown option '$1' (see --help)" ;;
  esac
done
[[ $repeats =~ ^[1-9][0-9]*$ ]] || study_die "--repeats must be a positive integer (got '$repeats')"
mkdir -p "$out" || study_die "cannot create '$out'"
out=$(cd "$out" && pwd)

list=$out/cases.list
: >"$list"
for rep in $(seq 1 "$repeats"); do
  for m in $meshes; do
    if [[ $(awk -v r="$ratio" 'BEGIN { print (r == 1) }') == 1 ]]; then mx=$m my=$m; else read -r mx my < <(square_grid "$m" "$ratio"); fi
    for scheme in collocation backward; do
      name=${scheme}_rep${rep}_m$m
      ellipse_nml "$out/cases/$name/$name.nml" "$ratio" "$mx" "$my" "$nu" "$scheme" "$alpha"
      echo "cases/$name/$name.nml" >>"$list"
    done
  done
done
echo "error_vs_time: $(wc -l <"$list") runs in $out"
"$study_here/run_cases.sh" "${slurm[@]}" "${jobs[@]}" "$list" "$out/runs.tab"
status=$?
[[ -s $out/runs.tab ]] || study_die "no table was produced"

python3 "$study_here/error_vs_time.py" "$out/runs.tab" >"$out/error_vs_time.dat" || study_die "error_vs_time.py failed"
cat "$out/error_vs_time.dat"
for scheme in collocation backward collocation+extrapolate backward+extrapolate; do
  awk -v s="$scheme" '!/^#/ && $1 == s' "$out/error_vs_time.dat" >"$out/plot_$scheme.dat"
done
if have_gnuplot; then
  gnuplot <<EOF
set terminal pngcairo size 860,600 font ',11'
set output '$out/error_vs_time.png'
set title "Relative error against run time (a/b = $ratio, nu = $nu; reference: Richardson limit)"
set xlabel 'wall time of one run [s] (median of $repeats)'
set ylabel '|C / C_{ref} - 1|'
set logscale xy
set format y '10^{%T}'
set grid
set key bottom left font ',9' box opaque
plot '$out/plot_collocation.dat' using 4:8 with linespoints lw 2 pt 5 lc 1 title 'collocation C11', \
     '$out/plot_collocation.dat' using 4:9 with linespoints lw 2 pt 7 lc 2 title 'collocation C22', \
     '$out/plot_collocation.dat' using 4:10 with linespoints lw 2 pt 9 lc 3 title 'collocation C23', \
     '$out/plot_backward.dat' using 4:8 with linespoints lw 2 dt 2 pt 4 lc 1 title 'backward C11', \
     '$out/plot_backward.dat' using 4:9 with linespoints lw 2 dt 2 pt 6 lc 2 title 'backward C22', \
     '$out/plot_backward.dat' using 4:10 with linespoints lw 2 dt 2 pt 8 lc 3 title 'backward C23', \
     '$out/plot_collocation+extrapolate.dat' using 4:8 with points pt 1 ps 2.5 lc 1 title 'extrapolate C11 (+ coll., x backw.)', \
     '$out/plot_collocation+extrapolate.dat' using 4:9 with points pt 1 ps 2.5 lc 2 title 'extrapolated C22', \
     '$out/plot_collocation+extrapolate.dat' using 4:10 with points pt 1 ps 2.5 lc 3 title 'extrapolated C23', \
     '$out/plot_backward+extrapolate.dat' using 4:8 with points pt 2 ps 2.5 lc 1 notitle, \
     '$out/plot_backward+extrapolate.dat' using 4:9 with points pt 2 ps 2.5 lc 2 notitle, \
     '$out/plot_backward+extrapolate.dat' using 4:10 with points pt 2 ps 2.5 lc 3 notitle
EOF
  gnuplot <<EOF
set terminal pngcairo size 860,600 font ',11'
set output '$out/error_vs_mesh.png'
set title "Relative error against mesh size (a/b = $ratio, nu = $nu)"
set xlabel 'h = 1/M (M x M grid)'
set ylabel '|C / C_{ref} - 1|'
set logscale xy
set format y '10^{%T}'
set grid
set key bottom left font ',9' box opaque
plot '$out/plot_collocation.dat' using (1./\$2):8 with linespoints lw 2 pt 5 lc 1 title 'collocation C11', \
     '$out/plot_collocation.dat' using (1./\$2):9 with linespoints lw 2 pt 7 lc 2 title 'collocation C22', \
     '$out/plot_collocation.dat' using (1./\$2):10 with linespoints lw 2 pt 9 lc 3 title 'collocation C23', \
     '$out/plot_backward.dat' using (1./\$2):8 with linespoints lw 2 dt 2 pt 4 lc 1 title 'backward C11', \
     '$out/plot_backward.dat' using (1./\$2):9 with linespoints lw 2 dt 2 pt 6 lc 2 title 'backward C22', \
     '$out/plot_backward.dat' using (1./\$2):10 with linespoints lw 2 dt 2 pt 8 lc 3 title 'backward C23', \
     0.05/x with lines lc 'gray' dt 3 title 'slope 1'
EOF
  echo "error_vs_time: plots $out/error_vs_time.png $out/error_vs_mesh.png"
  if ((docs)); then
    mkdir -p "$study_repo/docs/figures" "$study_repo/docs/data"
    cp "$out/error_vs_time.png" "$out/error_vs_mesh.png" "$study_repo/docs/figures/"
    cp "$out/error_vs_time.dat" "$study_repo/docs/data/error_vs_time.dat"
  fi
fi
exit $status
