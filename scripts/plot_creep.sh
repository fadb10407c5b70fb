#!/usr/bin/env bash
# Draw kcreep's FASTSIM outputs with gnuplot:
#   CASE_creep.png  -Fx/(mu Fn), -Fy/(mu Fn) and |F|/(mu Fn) against the creepage (xi, eta,
#                   or phi in 1/mm: of each point its largest component, in magnitude), one line
#                   per flexibility source and run of points along one creepage direction (e.g. a
#                   sweep); with combined creepage (two or more components in one point) -Fx and
#                   -Fy in two panels; with --contact CSV (compare_contact_slip.py --csv)
#                   CONTACT's points of that patch are added;
#   CASE_map.png    (with a .creepmap) the traction |p|/(mu pn) of row K of the creep table (one
#                   creepage and source; default 1), slip cells marked.
# usage: scripts/plot_creep.sh CASE.creep [--map CASE.creepmap [--row K]]
#                              [--contact CSV --patch NAME] [--out FOLDER] [--keep FOLDER]
# Output goes to the working folder (--out FOLDER).
# --keep FOLDER: keep there what gnuplot was given (the data files SOURCE.dat, whose
# columns are creepage -fx_mufn -fy_mufn f_mufn xi eta phi, and creep.gp, map.gp).
# scripts/plot_creep.sh --help: this text
usage() { awk 'NR > 1 && /^#/ { sub(/^# ?/, ""); print; next } NR > 1 { exit }' "${BASH_SOURCE[0]}"; }
for arg in "$@"; do case $arg in -h | --help) usage; exit 0 ;; --) break ;; esac; done
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
creep=${1:?usage: scripts/plot_creep.sh CASE.creep [--map M [--row K]] [--contact CSV --patch P]}
shift
map=''; row=1; contact=''; patch=''; out=.; keep=''
while [[ $# -gt 0 ]]; do
  case $1 in
    --map) map=$2; shift 2 ;;
    --row) row=$2; shift 2 ;;
    --contact) contact=$2; shift 2 ;;
    --patch) patch=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    --keep) keep=$2; shift 2 ;;
    *) echo "plot_creep.sh: unknown option $1" >&2; exit 2 ;;
  esac
done
command -v gnuplot >/dev/null || { echo "plot_creep.sh: gnuplot missing (run scripts/setup.sh)" >&2; exit 2; }
[[ -r $creep ]] || { echo "plot_creep.sh: cannot read $creep" >&2; exit 2; }
name=$(basename "${creep%.creep}")
work=$(mktemp -d)
trap '[[ -z $keep ]] || cp "$work"/* "$keep"/; rm -rf "$work"' EXIT
[[ -z $keep || -d $keep ]] || { echo "plot_creep.sh: --keep folder $keep does not exist" >&2; exit 2; }

python3 - "$creep" "$work" "$contact" "$patch" <<'EOP'
import csv, math, sys
creep, work, contact, patch = sys.argv[1:5]
NAMES = ('xi', 'eta', 'phi')


def along(xi, eta, phi):
    """The creepage of a point as the x axis: its largest component (xi, eta or
    phi, whichever is largest in magnitude; phi in 1/mm), in magnitude."""
    k = max(range(3), key=lambda i: abs((xi, eta, phi)[i]))
    return abs((xi, eta, phi)[k]), NAMES[k]


cols = None
out = {}
mu = None
used = set()
combined = False
for line in open(creep):
    if line.startswith('# mu ='):
        mu = float(line.split('=')[1].split(',')[0])
    if line.startswith('#'):
        words = line[1:].split()
        if 'xi' in words and 'fx_mufn' in words:
            cols = words
        continue
    if not line.strip():
        continue
    r = dict(zip(cols, line.split()))
    xi, eta, phi = float(r['xi']), float(r['eta']), float(r['phi'])
    combined = combined or sum(v != 0 for v in (xi, eta, phi)) > 1
    x, leading = along(xi, eta, phi)
    used.add(leading)
    fx, fy = float(r['fx_mufn']), float(r['fy_mufn'])
    norm = math.sqrt(xi * xi + eta * eta + phi * phi) or 1.0
    direction = tuple(round(v / norm, 9) for v in (xi, eta, phi))
    out.setdefault(r['source'], []).append((direction, (x, -fx, -fy, math.hypot(fx, fy), xi, eta, phi)))
for src, pts in out.items():
    # columns: creepage (x axis), -Fx/(mu Fn), -Fy/(mu Fn), |F|/(mu Fn), xi, eta, phi;
    # points in the table's order, a new line wherever the creepage direction changes
    with open(f'{work}/{src}.dat', 'w') as f:
        f.write('# creepage -fx_mufn -fy_mufn f_mufn xi eta phi\n')
        last = None
        for direction, p in pts:
            if last is not None and direction != last:
                f.write('\n')
            last = direction
            f.write('%g %g %g %g %g %g %g\n' % p)
xs = [p[1][0] for pts in out.values() for p in pts]
with open(f'{work}/sources', 'w') as f:
    f.write(' '.join(out))
with open(f'{work}/layout', 'w') as f:
    # panels (1: -Fx, -Fy and |F| together; 2: Fx and Fy apart, for combined
    # creepage), the x axis's words, log scale when the points span two decades
    names = [n for n in NAMES if n in used]
    label = ' or '.join(n + (' (1/mm)' if n == 'phi' else '') for n in names)
    if combined:
        label = 'creepage: each point\'s largest component, ' + label
    log = bool(xs) and min(xs) > 0 and max(xs) / min(xs) >= 100
    f.write('%d\n%s\n%d\n' % (2 if combined else 1, label, log))
if contact:
    with open(f'{work}/contact.dat', 'w') as f:
        for r in csv.DictReader(open(contact)):
            if r['patch'] != patch:
                continue
            xi, eta, phi = float(r['xi']), float(r['eta']), float(r['phi'])
            fx, fy = float(r['contact_fx']), float(r['contact_fy'])
            f.write('%g %g %g %g\n' % (along(xi, eta, phi)[0], -fx, -fy, math.hypot(fx, fy)))
EOP

sources=$(cat "$work/sources")
{ read -r panels; read -r xlabel; read -r logx; } <"$work/layout"
curves() {  # curves of column $1 (2: -Fx, 3: -Fy, 4: |F|), key words $2, dash type $3
  local s list=''
  for s in $sources; do list+="'$work/$s.dat' u 1:$1 w lp pt 7 ps 0.5 lw 2 dt $3 t '$2, $s', "; done
  [[ -s $work/contact.dat ]] && list+="'$work/contact.dat' u 1:$1 w p pt 5 ps 1.2 lc rgb 'black' t 'CONTACT $2', "
  echo "$list"
}
{
  echo "set terminal pngcairo size 900,$((panels == 2 ? 900 : 600)) font ',10' noenhanced"
  echo "set output '$out/${name}_creep.png'"
  echo "set xlabel \"$xlabel\""
  echo "set grid"
  echo "set key outside right"
  ((logx)) && echo "set logscale x"
  if ((panels == 2)); then
    echo "set multiplot layout 2,1 title \"$name: FASTSIM creep forces (combined creepage)\""
    echo "set ylabel \"-Fx / (mu Fn)\""
    plot=$(curves 2 '-Fx/(mu Fn)' 1); echo "plot ${plot%, }"
    echo "set ylabel \"-Fy / (mu Fn)\""
    plot=$(curves 3 '-Fy/(mu Fn)' 1); echo "plot ${plot%, }"
    echo "unset multiplot"
  else
    echo "set title \"$name: FASTSIM creep forces\""
    echo "set ylabel \"F / (mu Fn)\""
    plot="$(curves 4 '|F|/(mu Fn)' 1)$(curves 2 '-Fx/(mu Fn)' 2)$(curves 3 '-Fy/(mu Fn)' 3)"
    echo "plot ${plot%, }"
  fi
} >"$work/creep.gp"
gnuplot "$work/creep.gp"
echo "$out/${name}_creep.png"

if [[ -n $map ]]; then
  # block ROW (gnuplot's index is 0-based): |p|/(mu pn) per cell, slip cells as crosses
  mu=$(awk '/^# mu =/{gsub(",","",$4); print $4; exit}' "$creep")
  sub=$(grep '^# point' "$map" | sed -n "${row}p" | cut -c3-)
  cat >"$work/map.gp" <<EOG
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
  gnuplot "$work/map.gp"
  echo "$out/${name}_map.png"
fi
