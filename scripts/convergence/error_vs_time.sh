#!/usr/bin/env bash
# Error against run time: for each scheme and mesh, the relative error of
# C11, C22, C23 against the refined Kalker table (docs/data/kalker_refined.dat,
# whose 95 % uncertainty u is drawn as a band) and the time of the run;
# beside the fixed grids, kcreep's solved run under error control (only semi_a,
# semi_b, nu and method = 'iterative' given) and its accurate mode (target_error
# = 1e-4); a table
# and log-log plots (one curve per scheme and coefficient).
#
#   scripts/convergence/error_vs_time.sh [options]
#     --ratio 1             ellipse ratio a/b (c = 1); a node of the refined
#                           table (scripts/convergence/refined_reference.py)
#     --meshes "10 ... 160" grid sizes M (M x M cells; near-square cells when
#                           a/b != 1, about M*M cells)
#     --alpha 0.5           collocation point
#     --nu 0.25             Poisson's ratio (a node of the refined table)
#     --repeats 5           runs per point; the fastest time is reported
#     --out DIR             output folder [./studies/error_vs_time]
#     --jobs N              cases in parallel [1: timings of runs that share
#                           the cores with each other are not worth much]
#     --slurm "OPTS"        run through the SLURM back-end with these options
#     --help                this text
#     --docs                also copy plots and tables into docs/
# Timing: the runs hold the lock /tmp/kcreep-bench.lock (flock; set
# KCREEP_BENCH_LOCK to use another file), so that no two benchmarks of this
# machine run at once; times are kcreep's t_total (including its error
# estimate), the fastest of the repeats (other work on a shared machine only
# ever slows a run down).
# Writes DIR/runs.tab (every run), DIR/error_vs_time.dat, DIR/error_vs_time.png
# and DIR/error_vs_mesh.png.
set -uo pipefail
source "$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/study_lib.sh"

ratio=1 meshes="10 15 20 30 40 60 80 120 160" alpha=0.5 nu=0.25 repeats=5
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
reference=$(python3 "$study_here/refined_reference.py" "$ratio" "$nu") || study_die "no reference for a/b = $ratio, nu = $nu"
mkdir -p "$out" || study_die "cannot create '$out'"
out=$(cd "$out" && pwd)

# controlled_nml FILE [TARGET]: kcreep's own choice of grids (error control),
# solved (method = 'iterative': the default 'auto' would answer this ellipse
# from the refined table, the very reference of this study)
controlled_nml() {
  local file=$1 target=${2:-} a b
  a=$(awk -v r="$ratio" 'BEGIN { printf "%.15g", sqrt(r) }')
  b=$(awk -v r="$ratio" 'BEGIN { printf "%.15g", 1 / sqrt(r) }')
  mkdir -p "$(dirname "$file")"
  {
    echo "&patch semi_a = $a, semi_b = $b /"
    echo "&material nu = $nu /"
    echo "&solver method = 'iterative'${target:+, target_error = $target} /"
  } >"$file.new"
  if [[ -f $file ]] && cmp -s "$file" "$file.new"; then rm -f "$file.new"; else mv "$file.new" "$file"; fi
}

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
  controlled_nml "$out/cases/default_rep${rep}_m0/default_rep${rep}_m0.nml"
  controlled_nml "$out/cases/accurate_rep${rep}_m0/accurate_rep${rep}_m0.nml" 1e-4
  echo "cases/default_rep${rep}_m0/default_rep${rep}_m0.nml" >>"$list"
  echo "cases/accurate_rep${rep}_m0/accurate_rep${rep}_m0.nml" >>"$list"
done
echo "error_vs_time: $(wc -l <"$list") runs in $out"
lock=()
if ((${#slurm[@]} == 0)); then
  if command -v flock >/dev/null; then
    lock=(flock "${KCREEP_BENCH_LOCK:-/tmp/kcreep-bench.lock}")
  else
    echo "error_vs_time: flock not found: timing without the benchmark lock" >&2
  fi
fi
"${lock[@]}" "$study_repo/scripts/run_cases.sh" "${slurm[@]}" "${jobs[@]}" "$list" "$out/runs.tab"
status=$?
[[ -s $out/runs.tab ]] || study_die "no table was produced"

python3 "$study_here/error_vs_time.py" --ratio "$ratio" --nu "$nu" "$out/runs.tab" >"$out/error_vs_time.dat" || study_die "error_vs_time.py failed"
cat "$out/error_vs_time.dat"
for scheme in collocation backward collocation+extrapolate backward+extrapolate default accurate; do
  awk -v s="$scheme" '!/^#/ && $1 == s' "$out/error_vs_time.dat" >"$out/plot_$scheme.dat"
done
if have_gnuplot; then
  # the reference's relative uncertainty u/C of C11, C22, C23: errors below it cannot be judged
  read -r u11 u22 u23 < <(awk '{ printf "%.6g %.6g %.6g\n", $2 / $1, $4 / $3, $6 / $5 }' <<<"$reference")
  band="$u11 with lines lc 1 dt 3 lw 1.5 title 'u of the reference (C11, C22, C23)', $u22 with lines lc 2 dt 3 lw 1.5 notitle, $u23 with lines lc 3 dt 3 lw 1.5 notitle"
  gnuplot <<EOF
set terminal pngcairo size 900,640 font ',11'
set output '$out/error_vs_time.png'
set title "Relative error against run time (a/b = $ratio, nu = $nu; reference: refined Kalker table)"
set xlabel 'time of one run [s] (kcreep t\\_total, fastest of $repeats)'
set ylabel '|C / C_{ref} - 1|'
set logscale xy
set format y '10^{%T}'
set yrange [1e-5:1]
set xrange [0.003:30]
set grid
set key top right font ',9' box opaque
plot '$out/plot_collocation.dat' using 4:8 with linespoints lw 2 pt 5 lc 1 title 'collocation (alpha = $alpha) C11', \
     '$out/plot_collocation.dat' using 4:9 with linespoints lw 2 pt 7 lc 2 title 'collocation C22', \
     '$out/plot_collocation.dat' using 4:10 with linespoints lw 2 pt 9 lc 3 title 'collocation C23', \
     '$out/plot_backward.dat' using 4:8 with linespoints lw 2 dt 2 pt 4 lc 1 title 'backward C11', \
     '$out/plot_backward.dat' using 4:9 with linespoints lw 2 dt 2 pt 6 lc 2 title 'backward C22', \
     '$out/plot_backward.dat' using 4:10 with linespoints lw 2 dt 2 pt 8 lc 3 title 'backward C23', \
     '$out/plot_collocation+extrapolate.dat' using 4:8 with points pt 1 ps 2 lc 1 title 'extrapolate (+ coll., x backw.) C11', \
     '$out/plot_collocation+extrapolate.dat' using 4:9 with points pt 1 ps 2 lc 2 notitle, \
     '$out/plot_collocation+extrapolate.dat' using 4:10 with points pt 1 ps 2 lc 3 notitle, \
     '$out/plot_backward+extrapolate.dat' using 4:8 with points pt 2 ps 2 lc 1 notitle, \
     '$out/plot_backward+extrapolate.dat' using 4:9 with points pt 2 ps 2 lc 2 notitle, \
     '$out/plot_backward+extrapolate.dat' using 4:10 with points pt 2 ps 2 lc 3 notitle, \
     '$out/plot_default.dat' using 4:8 with points pt 13 ps 3 lc 1 title 'error control, solved (target 1e-3) C11, C22, C23', \
     '$out/plot_default.dat' using 4:9 with points pt 13 ps 3 lc 2 notitle, \
     '$out/plot_default.dat' using 4:10 with points pt 13 ps 3 lc 3 notitle, \
     '$out/plot_accurate.dat' using 4:8 with points pt 11 ps 3 lc 1 title 'error control, solved (target 1e-4)', \
     '$out/plot_accurate.dat' using 4:9 with points pt 11 ps 3 lc 2 notitle, \
     '$out/plot_accurate.dat' using 4:10 with points pt 11 ps 3 lc 3 notitle, \
     $band
EOF
  gnuplot <<EOF
set terminal pngcairo size 900,640 font ',11'
set output '$out/error_vs_mesh.png'
set title "Relative error against mesh size (a/b = $ratio, nu = $nu; reference: refined Kalker table)"
set xlabel 'h = 1/M (M x M grid)'
set ylabel '|C / C_{ref} - 1|'
set logscale xy
set format y '10^{%T}'
set grid
set key top left font ',9' box opaque
plot '$out/plot_collocation.dat' using (1./\$2):8 with linespoints lw 2 pt 5 lc 1 title 'collocation C11', \
     '$out/plot_collocation.dat' using (1./\$2):9 with linespoints lw 2 pt 7 lc 2 title 'collocation C22', \
     '$out/plot_collocation.dat' using (1./\$2):10 with linespoints lw 2 pt 9 lc 3 title 'collocation C23', \
     '$out/plot_backward.dat' using (1./\$2):8 with linespoints lw 2 dt 2 pt 4 lc 1 title 'backward C11', \
     '$out/plot_backward.dat' using (1./\$2):9 with linespoints lw 2 dt 2 pt 6 lc 2 title 'backward C22', \
     '$out/plot_backward.dat' using (1./\$2):10 with linespoints lw 2 dt 2 pt 8 lc 3 title 'backward C23', \
     0.5*x with lines lc 'gray' dt 4 title 'slope 1', \
     $band
EOF
  echo "error_vs_time: plots $out/error_vs_time.png $out/error_vs_mesh.png"
  if ((docs)); then
    mkdir -p "$study_repo/docs/figures" "$study_repo/docs/data"
    cp "$out/error_vs_time.png" "$out/error_vs_mesh.png" "$study_repo/docs/figures/"
    cp "$out/error_vs_time.dat" "$study_repo/docs/data/error_vs_time.dat"
  fi
fi
exit $status
