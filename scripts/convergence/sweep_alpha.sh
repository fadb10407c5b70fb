#!/usr/bin/env bash
# The paper's figure 2: f11, f22, f23 of the collocation scheme against the
# collocation point alpha, for three ellipse ratios, as ratios to the refined
# Kalker table (docs/data/kalker_refined.dat; the ratios and nu must be its
# nodes, see scripts/convergence/refined_reference.py).
#
#   scripts/convergence/sweep_alpha.sh [options]
#     --ratios "0.2 1 5"   ellipse ratios a/b (c = sqrt(a b) = 1)
#     --alphas "..."       collocation points, in (-1, 1)
#     --grid 80            the paper's grid: mx = my = 80 (its N = 6400)
#     --no-square          skip the near-square-cell grids (about grid^2
#                          cells, dx ~ dy) run beside the paper's grid
#     --nu 0.25            Poisson's ratio
#     --out DIR            output folder [./studies/sweep_alpha]
#     --jobs N             cases in parallel [number of cores]
#     --slurm "OPTS"       run through the SLURM back-end with these options
#     --help               this text
#     --docs               also copy the plots and the table into docs/
#     --replot             no runs: redraw the plots from DIR/sweep_alpha.tab
#                          (e.g. after the reference changed)
# Writes DIR/sweep_alpha.tab (all rows) and DIR/sweep_alpha_*.png.
set -uo pipefail
source "$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/study_lib.sh"

ratios="0.2 1 5"
alphas="-0.9 -0.5 0 0.2 0.4 0.5 0.6 0.7 0.8 0.9"
grid=80 nu=0.25 square=1 out=$PWD/studies/sweep_alpha jobs=() slurm=() docs=0 replot=0
while (($#)); do
  case $1 in
    --ratios) ratios=$2; shift 2 ;;
    --alphas) alphas=$2; shift 2 ;;
    --grid) grid=$2; shift 2 ;;
    --no-square) square=0; shift ;;
    --replot) replot=1; shift ;;
    *) study_option "$@"; shift "$study_used" ;;
  esac
done
# the reference of each ratio: "ratio c11 u11 c22 u22 c23 u23;" ...
refs=$(study_refs "$nu" $ratios) || exit 2
out=$(study_out_dir "$out") || exit 2

status=0
if ((replot)); then
  [[ -s $out/sweep_alpha.tab ]] || study_die "--replot: no table $out/sweep_alpha.tab to plot"
else
  list=$out/cases.list
  : >"$list"
  for r in $ratios; do
    grids=$(study_grids "$grid" "$r" "$square")
    for g in $grids; do
      IFS=: read -r kind mx my <<<"$g"
      for al in $alphas; do
        name=r${r}_${kind}_a${al}
        ellipse_nml "$out/cases/$name/$name.nml" "$r" "$mx" "$my" "$nu" collocation "$al"
        echo "cases/$name/$name.nml" >>"$list"
      done
    done
  done
  echo "sweep_alpha: $(wc -l <"$list") points in $out"
  "$study_repo/scripts/run_cases.sh" "${slurm[@]}" "${jobs[@]}" "$list" "$out/sweep_alpha.tab"
  status=$?
fi
[[ -s $out/sweep_alpha.tab ]] || study_die "no table was produced"

# Plot data: per ratio and grid kind, alpha and the three ratios to the refined values.
columns "$out/sweep_alpha.tab" case mx my alpha c11 c22 c23 klt11 klt22 klt23 verdict |
  awk -v out="$out" -v refs="$refs" "$study_refs_awk"'
       { split($1, p, "_"); r = substr(p[1], 2); f = out "/plot_" p[1] "_" p[2] ".dat"
         print $4, $5 / ref11[r], $6 / ref22[r], $7 / ref23[r], $2, $3, $11 > f }'
if have_gnuplot; then
  for coef in 11 22 23; do
    col=$((coef == 11 ? 2 : coef == 22 ? 3 : 4))
    plots=() zplots=() i=0
    for f in "$out"/plot_*.dat; do
      t=$(basename "$f" .dat); t=${t#plot_r}; t=${t/_/, }
      i=$((i + 1))
      plots+=("'$f' using 1:$col with linespoints lw 2 pt $((i + 4)) title 'a/b = $t'")
      zplots+=("'$f' using (\$1 > 0 ? \$1 : 1/0):$col with linespoints lw 2 pt $((i + 4)) title 'a/b = $t'")
    done
    gnuplot <<EOF
set terminal pngcairo size 800,560 font ',11'
set output '$out/sweep_alpha_f$coef.png'
set title "Collocation: f$coef / refined value against alpha (nu = $nu, ${grid}x${grid} paper grid; square: near-square cells)"
set xlabel 'alpha (collocation point x_i + alpha dx/2; + = leading edge)'
set ylabel 'f$coef / f$coef(refined Kalker table)'
set grid
set key bottom right
set yrange [-1.5:1.5]
set xrange [-1:1]
plot 1 with lines lc 'black' dt 2 notitle, $(IFS=,; echo "${plots[*]}")
EOF
    # the useful window alpha > 0, where the solution is physical
    gnuplot <<EOF
set terminal pngcairo size 800,560 font ',11'
set output '$out/sweep_alpha_f${coef}_zoom.png'
set title "Collocation, alpha > 0: f$coef / refined value (nu = $nu)"
set xlabel 'alpha'
set ylabel 'f$coef / f$coef(refined Kalker table)'
set grid
set key bottom left
set xrange [0.05:0.95]
set yrange [0.85:1.15]
plot 1 with lines lc 'black' dt 2 notitle, $(IFS=,; echo "${zplots[*]}")
EOF
  done
  echo "sweep_alpha: plots $out/sweep_alpha_f{11,22,23}{,_zoom}.png"
  if ((docs)); then
    study_to_docs "$out/sweep_alpha.tab" sweep_alpha "$out"/sweep_alpha_*.png
  fi
fi
exit $status
