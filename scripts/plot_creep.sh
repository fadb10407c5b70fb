#!/usr/bin/env bash
# Draw kcreep's FASTSIM outputs with gnuplot:
#   CASE_creep.png  -Fx/(mu Fn), -Fy/(mu Fn) and |F|/(mu Fn) against the normalised creepage
#                   |(f11 xi, f22 eta + f23 phi)| / (mu Fn) (the linear theory's force over mu Fn),
#                   one line per flexibility source; with --contact CSV (compare_contact_slip.py --csv)
#                   CONTACT's points of that patch are added;
#                   (a line per run of points along one creepage direction, e.g. a sweep);
#   CASE_map.png    (with a .creepmap) the traction |p|/(mu pn) of row K of the creep table (one
#                   creepage and source; default 1), slip cells marked.
# usage: scripts/plot_creep.sh CASE.creep [--table CASE.tab] [--map CASE.creepmap [--row K]]
#                              [--contact CSV --patch NAME] [--out FOLDER]
# The table defaults to the .creep's name with .tab; output goes to the working folder.
# scripts/plot_creep.sh --help: this text
usage() { awk 'NR > 1 && /^#/ { sub(/^# ?/, ""); print; next } NR > 1 { exit }' "${BASH_SOURCE[0]}"; }
for arg in "$@"; do case $arg in -h | --help) usage; exit 0 ;; --) break ;; esac; done
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
creep=${1:?usage: scripts/plot_creep.sh CASE.creep [--table T] [--map M [--row K]] [--contact CSV --patch P]}
shift
table=${creep%.creep}.tab
map=''; row=1; contact=''; patch=''; out=.
while [[ $# -gt 0 ]]; do
  case $1 in
    --table) table=$2; shift 2 ;;
    --map) map=$2; shift 2 ;;
    --row) row=$2; shift 2 ;;
    --contact) contact=$2; shift 2 ;;
    --patch) patch=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    *) echo "plot_creep.sh: unknown option $1" >&2; exit 2 ;;
  esac
done
command -v gnuplot >/dev/null || { echo "plot_creep.sh: gnuplot missing (run scripts/setup.sh)" >&2; exit 2; }
[[ -r $creep ]] || { echo "plot_creep.sh: cannot read $creep" >&2; exit 2; }
[[ -r $table ]] || { echo "plot_creep.sh: cannot read the coefficient table $table (--table)" >&2; exit 2; }
name=$(basename "${creep%.creep}")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

python3 - "$creep" "$table" "$work" "$contact" "$patch" <<'EOP'
import csv, math, sys
creep, table, work, contact, patch = sys.argv[1:6]
cols = None
row = None
for line in open(table):
    if line.startswith('#'):
        cols = line[1:].split()
    elif line.strip():
        row = dict(zip(cols, line.split()))
f11, f22, f23 = (float(row[k]) for k in ('f11', 'f22', 'f23'))
cols = None
out = {}
mu = None
for line in open(creep):
    if line.startswith('# mu ='):
        mu = float(line.split('=')[1].split(',')[0])
    if line.startswith('#'):
        cols = line[1:].split()
        continue
    r = dict(zip(cols, line.split()))
    xi, eta, phi = float(r['xi']), float(r['eta']), float(r['phi'])
    s = math.hypot(f11 * xi, f22 * eta + f23 * phi) / (mu * float(r['fn']))
    fx, fy = float(r['fx_mufn']), float(r['fy_mufn'])
    norm = math.sqrt(xi * xi + eta * eta + phi * phi) or 1.0
    direction = tuple(round(v / norm, 9) for v in (xi, eta, phi))
    out.setdefault(r['source'], []).append((direction, (s, -fx, -fy, math.hypot(fx, fy))))
for src, pts in out.items():
    # points in the table's order; a new line wherever the creepage direction changes
    with open(f'{work}/{src}.dat', 'w') as f:
        last = None
        for direction, p in pts:
            if last is not None and direction != last:
                f.write('\n')
            last = direction
            f.write('%g %g %g %g\n' % p)
with open(f'{work}/sources', 'w') as f:
    f.write(' '.join(out))
if contact:
    with open(f'{work}/contact.dat', 'w') as f:
        for r in csv.DictReader(open(contact)):
            if r['patch'] != patch:
                continue
            xi, eta, phi = float(r['xi']), float(r['eta']), float(r['phi'])
            s = math.hypot(f11 * xi, f22 * eta + f23 * phi) / (float(r['mu']) * float(r['fn']))
            fx, fy = float(r['contact_fx']), float(r['contact_fy'])
            f.write('%g %g %g %g\n' % (s, -fx, -fy, math.hypot(fx, fy)))
EOP

sources=$(cat "$work/sources")
plot=''
for s in $sources; do
  plot+="'$work/$s.dat' u 1:4 w lp pt 7 ps 0.5 lw 2 t '|F|/(mu Fn), L: $s', "
  plot+="'$work/$s.dat' u 1:2 w l dt 2 t '-Fx/(mu Fn), $s', '$work/$s.dat' u 1:3 w l dt 3 t '-Fy/(mu Fn), $s', "
done
[[ -s $work/contact.dat ]] && plot+="'$work/contact.dat' u 1:4 w p pt 5 ps 1.2 lc rgb 'black' t 'CONTACT |F|/(mu Fn)', "
gnuplot <<EOG
set terminal pngcairo size 900,600 font ",10" noenhanced
set output '$out/${name}_creep.png'
set title "$name: FASTSIM creep forces"
set xlabel "|(f11 xi, f22 eta + f23 phi)| / (mu Fn)"
set ylabel "F / (mu Fn)"
set logscale x
set grid
set key outside right
plot ${plot%, }
EOG
echo "$out/${name}_creep.png"

if [[ -n $map ]]; then
  # block ROW (gnuplot's index is 0-based): |p|/(mu pn) per cell, slip cells as crosses
  mu=$(awk '/^# mu =/{gsub(",","",$4); print $4; exit}' "$creep")
  sub=$(grep '^# point' "$map" | sed -n "${row}p" | cut -c3-)
  gnuplot <<EOG
set terminal pngcairo size 800,700 font ",10" noenhanced
set output '$out/${name}_map.png'
set title "$name: traction |p|/(mu pn), creep table row $row (crosses: slip)\n$sub"
set xlabel "x (rolling direction, leading edge at +x)"
set ylabel "y"
set size ratio -1
set cbrange [0:1]
set palette rgbformulae 33,13,10
plot '$map' index ($row - 1) u 3:4:(sqrt(\$6**2 + \$7**2) / ($mu * \$5)) w p pt 5 ps 1.3 palette notitle, \
     '' index ($row - 1) u 3:(\$8 == 2 ? \$4 : NaN) w p pt 2 ps 0.6 lc rgb 'black' notitle
EOG
  echo "$out/${name}_map.png"
fi
