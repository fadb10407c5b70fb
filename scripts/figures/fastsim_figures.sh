#!/usr/bin/env bash
# FASTSIM against CONTACT with friction: runs scripts/compare_contact_slip.py on the
# slip runs (../shared/contact-slip, ../shared/contact-samples/ellipse_a6_b4_slip) and
# draws fastsim_contact.png (F/(mu Fn) against the normalised creepage,
# one line per flexibility source, CONTACT's points) and fastsim_combined.png (the
# error of each combined case under the weighted, the separate and the aligned
# flexibility rule).
#   scripts/figures/fastsim_figures.sh [--out DIR] [--data DIR] [SHARED_FOLDER]
#     --out DIR      the figures (default build/figures; docs/figures to update docs/fastsim.md)
#     --data DIR     the CSV tables and the summary (default: the --out folder; docs/data for the docs)
#     SHARED_FOLDER  CONTACT's runs (default ../shared beside the repository)
#   scripts/figures/fastsim_figures.sh --help                this text
usage() { awk 'NR > 1 && /^#/ { sub(/^# ?/, ""); print; next } NR > 1 { exit }' "${BASH_SOURCE[0]}"; }
for arg in "$@"; do case $arg in -h | --help) usage; exit 0 ;; --) break ;; esac; done
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
figs=$here/build/figures data=""
while (($#)); do
  case $1 in
    --out | --data) [[ $# -ge 2 ]] || { echo "fastsim_figures.sh: error: $1 needs a folder" >&2; exit 2; }
      if [[ $1 == --out ]]; then figs=$2; else data=$2; fi; shift 2 ;;
    -*) echo "fastsim_figures.sh: error: unknown option '$1' (see --help)" >&2; exit 2 ;;
    *) break ;;
  esac
done
data=${data:-$figs}
mkdir -p "$figs" "$data" && figs=$(cd "$figs" && pwd) && data=$(cd "$data" && pwd)
shared=$(cd "${1:-$here/../shared}" && pwd)
export KCREEP=${KCREEP:-$here/build/kcreep}
export KCREEP_FASTSIM_CURVE=${KCREEP_FASTSIM_CURVE:-$here/build/kcreep_fastsim_curve}
command -v gnuplot >/dev/null || { echo "fastsim_figures.sh: gnuplot missing (run scripts/setup.sh)" >&2; exit 2; }
s=$shared/contact-slip
python3 "$here/scripts/compare_contact_slip.py" --quiet --csv "$data/fastsim_contact_slip.csv" \
  --curves "$data/fastsim_curves.csv" \
  "$s/circle/circle_mu0p3.out" "$s/ellipse_ab0p5/ellipse_ab0p5_mu0p3.out" \
  "$s/kidney/kidney_mu0p3.out" "$s/twin/twin_mu0p3.out" \
  "$shared/contact-samples/ellipse_a6_b4_slip.out" > "$data/fastsim_contact_slip_summary.txt"
cat "$data/fastsim_contact_slip_summary.txt"

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
python3 - "$data" "$work" <<'EOP'
import csv, sys
data, work = sys.argv[1], sys.argv[2]
comp_force = {'xi': 'fx_mufn', 'eta': 'fy_mufn', 'phi': 'fy_mufn'}
files = {}
for r in csv.DictReader(open(f'{data}/fastsim_curves.csv')):
    key = f"{work}/{r['patch']}_{r['component']}_{r['source']}_{r['rule']}.dat"
    files.setdefault(key, []).append(f"{r['normalised']} {-float(r[comp_force[r['component']]])}")
coef = {}
for r in csv.DictReader(open(f'{data}/fastsim_curves.csv')):
    if r['source'] == 'exact' and r['rule'] == 'separate':
        coef[(r['patch'], r['component'])] = float(r['normalised']) / float(r['creepage'])
for r in csv.DictReader(open(f'{data}/fastsim_contact_slip.csv')):
    if r['kind'] != 'pure':
        continue
    for comp, col in (('xi', 'contact_fx'), ('eta', 'contact_fy'), ('phi', 'contact_fy')):
        v = float(r[comp])
        if v != 0 and (r['patch'], comp) in coef:
            files.setdefault(f"{work}/{r['patch']}_{comp}_contact.dat", []).append(
                f"{v * coef[(r['patch'], comp)]} {-float(r[col])}")
with open(f'{work}/combined.dat', 'w') as f:
    for k, r in enumerate(r for r in csv.DictReader(open(f'{data}/fastsim_contact_slip.csv')) if r['kind'] == 'combined'):
        f.write(f"{k} {r['patch'].replace('_mu0p3', '')}:{r['case']} {r['exact_weighted_err']} {r['exact_separate_err']} "
                f"{r['exact_aligned_err']} {r['box_aligned_err']} {r['moments_aligned_err']}\n")
for k, v in files.items():
    open(k, 'w').write('\n'.join(v) + '\n')
EOP

cd "$work"
gnuplot <<'EOG'
set terminal pngcairo size 1350,1500 font ",10"
set output 'fastsim_contact.png'
set multiplot layout 4,3 title "FASTSIM (separate flexibilities) on CONTACT's grid and pressure against CONTACT, mu = 0.3"
set logscale x
set format x "10^{%L}"
set key top left
set grid
set yrange [0:1.05]
do for [p in "circle_mu0p3 ellipse_ab0p5_mu0p3 kidney_mu0p3 twin_mu0p3"] {
  do for [c in "xi eta phi"] {
    lab = (c eq "xi") ? "-Fx/(mu Fn)" : "-Fy/(mu Fn)"
    nrm = (c eq "xi") ? "xi f11/(mu Fn)" : ((c eq "eta") ? "eta f22/(mu Fn)" : "phi f23/(mu Fn)")
    set title sprintf("%s, pure %s", p[1:strstrt(p, "_mu")-1], c) noenhanced
    set xlabel nrm
    set ylabel lab
    plot sprintf("%s_%s_exact_separate.dat", p, c) w l lw 2 lc rgb "#1f77b4" t "exact L", \
         sprintf("%s_%s_box_separate.dat", p, c) w l lw 1.5 dt 2 lc rgb "#d62728" t "box ellipse L", \
         sprintf("%s_%s_moments_separate.dat", p, c) w l lw 1.5 dt 3 lc rgb "#2ca02c" t "moment ellipse L", \
         sprintf("%s_%s_contact.dat", p, c) w p pt 7 ps 1.1 lc rgb "black" t "CONTACT"
  }
}
unset multiplot
set output 'fastsim_combined.png'
set terminal pngcairo size 1100,500 font ",10"
unset logscale x
set format x "%g"
set xlabel ""
set ylabel "|F(FASTSIM) - F(CONTACT)| / (mu Fn)  [%]"
set termoption noenhanced
set title "Combined creepages (cases 20-24 of each patch): error of FASTSIM with the patch's exact L"
set style data histogram
set style histogram clustered gap 1
set style fill solid 0.8 border -1
set yrange [0:*]
set xtics rotate by -45
set key top right
plot 'combined.dat' u 3:xtic(2) t "weighted L (Kalker 1982)" lc rgb "#d62728", \
     '' u 4 t "separate L1 L2 L3" lc rgb "#1f77b4", \
     '' u 5 t "aligned L1 L2 L3 (default)" lc rgb "#9467bd", \
     '' u 6 t "aligned, box ellipse L" lc rgb "#ff7f0e", \
     '' u 7 t "aligned, moment ellipse L" lc rgb "#2ca02c"
EOG
cp fastsim_contact.png fastsim_combined.png "$figs/"

# the crescent example: its curves for the three flexibility sources, and a traction map
cp "$here/input/crescent.mask" .
sed "s|input/crescent.mask|crescent.mask|" "$here/input/crescent.nml" > crescent.nml
"$KCREEP" crescent.nml > /dev/null 2>&1
"$here/scripts/plot_creep.sh" crescent.creep --out . > /dev/null
cat > crescent_map.nml <<'EON'
&patch shape = 'mask', mask_file = 'crescent.mask' /
&material g = 82000, nu = 0.28 /
&solver scheme = 'backward' /
&fastsim mu = 0.3, fn = 10000, creepages = 4e-4 4e-4 0, maps = .true. /
EON
"$KCREEP" crescent_map.nml > /dev/null 2>&1
"$here/scripts/plot_creep.sh" crescent_map.creep --map crescent_map.creepmap --row 1 --out . > /dev/null
cp crescent_creep.png "$figs/fastsim_crescent_curves.png"
cp crescent_map_map.png "$figs/fastsim_crescent_map.png"
echo "figures: $figs/fastsim_contact.png $figs/fastsim_combined.png $figs/fastsim_crescent_curves.png $figs/fastsim_crescent_map.png"
