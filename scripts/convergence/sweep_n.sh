#!/usr/bin/env bash
# The paper's figures 3 and 4: the coefficients against the mesh size, for
# the collocation scheme (alpha = 0.5) and the backward scheme, three ellipse
# ratios, the paper's mx = my grids and near-square-cell grids, against the
# refined Kalker table (docs/data/kalker_refined.dat; the ratios and nu must
# be its nodes, see scripts/convergence/refined_reference.py); then the order of
# convergence measured against that reference (scripts/convergence/convergence_order.py).
#
#   scripts/convergence/sweep_n.sh [options]
#     --ratios "0.2 1 5"     ellipse ratios a/b (c = sqrt(a b) = 1)
#     --meshes "10 ... 80"   grid sizes M: the paper's grid is M x M; the
#                            near-square grid has about M*M cells, dx ~ dy
#     --alpha 0.5            collocation point
#     --no-square            only the paper's M x M grids
#     --nu 0.25              Poisson's ratio
#     --out DIR              output folder [./studies/sweep_n]
#     --jobs N               cases in parallel [number of cores]
#     --slurm "OPTS"         run through the SLURM back-end with these options
#     --help                 this text
#     --docs                 also copy plots and tables into docs/
# Going further: --meshes "10 15 20 30 40 60 80 120 160" (160 x 160 needs
# about 10 GB and minutes per point with the dense solver).
# Writes DIR/sweep_n.tab, DIR/order.dat and DIR/sweep_n_*.png.
set -uo pipefail
source "$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/study_lib.sh"

ratios="0.2 1 5"
meshes="10 15 20 30 40 60 80"
alpha=0.5 nu=0.25 square=1 out=$PWD/studies/sweep_n jobs=() slurm=() docs=0
while (($#)); do
  case $1 in
    --ratios) ratios=$2; shift 2 ;;
    --meshes) meshes=$2; shift 2 ;;
    --alpha) alpha=$2; shift 2 ;;
    --no-square) square=0; shift ;;
    *) study_option "$@"; shift "$study_used" ;;
  esac
done
# the reference of each ratio: "ratio c11 u11 c22 u22 c23 u23;" ...
refs=$(study_refs "$nu" $ratios) || exit 2
out=$(study_out_dir "$out") || exit 2

list=$out/cases.list
: >"$list"
# largest meshes first: the long points start early and the pool stays full
for m in $(tr ' ' '\n' <<<"$meshes" | sort -rn); do
  for r in $ratios; do
    grids=$(study_grids "$m" "$r" "$square")
    for g in $grids; do
      IFS=: read -r kind mx my <<<"$g"
      for scheme in collocation backward; do
        name=r${r}_${kind}_${scheme}_m$m
        ellipse_nml "$out/cases/$name/$name.nml" "$r" "$mx" "$my" "$nu" "$scheme" "$alpha"
        echo "cases/$name/$name.nml" >>"$list"
      done
    done
  done
done
echo "sweep_n: $(wc -l <"$list") points in $out"
"$study_repo/scripts/run_cases.sh" "${slurm[@]}" "${jobs[@]}" "$list" "$out/sweep_n.tab"
status=$?
[[ -s $out/sweep_n.tab ]] || study_die "no table was produced"

python3 "$study_here/convergence_order.py" --nu "$nu" "$out/sweep_n.tab" >"$out/order.dat" ||
  study_die "convergence_order.py failed"
cat "$out/order.dat"

# Plot data: one file per series, rows sorted by mesh M: M, C/C_ref for C11, C22, C23 (as computed), ...
rm -f "$out"/plot_*.dat
columns "$out/sweep_n.tab" case mx my n c11 c22 c23 klt11 klt22 klt23 t_total verdict |
  awk -v out="$out" -v refs="$refs" "$study_refs_awk"'
       { split($1, p, "_"); r = substr(p[1], 2); m = substr(p[4], 2); f = out "/plot_" p[1] "_" p[2] "_" p[3] ".dat"
         print m, $5 / ref11[r], $6 / ref22[r], $7 / ref23[r], $2, $3, $4, $11, $12 > f }'
# the largest relative uncertainty of the reference over the ratios, per coefficient
read -r u11 u22 u23 < <(awk -v refs="$refs" 'BEGIN { n = split(refs, rr, ";"); for (i = 1; i <= n; i++) if (split(rr[i], w, " ") == 7)
         { if (w[3] / w[2] > a) a = w[3] / w[2]; if (w[5] / w[4] > b) b = w[5] / w[4]; if (w[7] / w[6] > c) c = w[7] / w[6] }
         printf "%.6g %.6g %.6g\n", a, b, c }')
for f in "$out"/plot_*.dat; do sort -n -o "$f" "$f"; done
if have_gnuplot; then
  for coef in 11 22 23; do
    col=$((coef == 11 ? 2 : coef == 22 ? 3 : 4))
    case $coef in 11) u=$u11 ;; 22) u=$u22 ;; *) u=$u23 ;; esac
    for scheme in collocation backward; do
      plots=() i=0
      for f in "$out"/plot_*_"$scheme".dat; do
        t=$(basename "$f" .dat); t=${t#plot_r}; t=${t%_*}; t=${t/_/, }
        i=$((i + 1))
        plots+=("'$f' using (\$1*\$1):$col with linespoints lw 2 pt $((i + 4)) title 'a/b = $t'")
      done
      label=$scheme
      [[ $scheme == collocation ]] && label="collocation, alpha = $alpha"
      gnuplot <<EOF
set terminal pngcairo size 800,560 font ',11'
set output '$out/sweep_n_${scheme}_f$coef.png'
set title "$label: f$coef / refined value against N = M x M grid cells (nu = $nu)"
set xlabel 'N (cells of the bounding grid)'
set ylabel 'f$coef / f$coef(refined Kalker table)'
set logscale x
set grid
set key top right
plot 1 with lines lc 'black' dt 2 notitle, 1 - $u with lines lc 'black' dt 3 title '1 +- u (the reference, largest of the ratios)', 1 + $u with lines lc 'black' dt 3 notitle, 0.99 with lines lc 'gray' dt 3 notitle, 1.01 with lines lc 'gray' dt 3 notitle, $(IFS=,; echo "${plots[*]}")
EOF
    done
  done
  echo "sweep_n: plots $out/sweep_n_{collocation,backward}_f{11,22,23}.png"
  if ((docs)); then
    study_to_docs "$out/sweep_n.tab" sweep_n "$out"/sweep_n_*.png
  fi
fi
exit $status
