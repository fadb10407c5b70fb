#!/usr/bin/env bash
# Redraw the figures of docs/method.md: the centre-row traction of the three
# discretisations on the unit circle and the y-oscillation of the collocation
# scheme on elongated cells.
#   scripts/figures/method_figures.sh [OUTPUT_FOLDER]   default OUTPUT_FOLDER: build/figures
#   scripts/figures/method_figures.sh docs/figures      to update docs/method.md's figures
#   scripts/figures/method_figures.sh --help            this text
# Needs build/kcreep (or $KCREEP) and gnuplot. Exit 2 when either is missing
# or OUTPUT_FOLDER cannot be made.
usage() { awk 'NR > 1 && /^#/ { sub(/^# ?/, ""); print; next } NR > 1 { exit }' "${BASH_SOURCE[0]}"; }
for arg in "$@"; do case $arg in -h | --help) usage; exit 0 ;; --) break ;; esac; done
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
kcreep=${KCREEP:-$here/build/kcreep}
(($# <= 1)) || { echo "method_figures.sh: error: at most one argument, OUTPUT_FOLDER (see --help)" >&2; exit 2; }
out=${1:-$here/build/figures}
mkdir -p "$out" 2>/dev/null || { echo "method_figures.sh: error: cannot make the folder '$out'" >&2; exit 2; }
out=$(cd "$out" && pwd)
[[ -x $kcreep ]] || { echo "method_figures.sh: no kcreep at $kcreep (run scripts/setup.sh)" >&2; exit 2; }
command -v gnuplot >/dev/null || { echo "method_figures.sh: gnuplot missing (run scripts/setup.sh)" >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
while read -r name scheme alpha a b; do
  cat > "$name.nml" <<EON
&patch semi_a=$a, semi_b=$b, mx=40, my=40 /
&material nu=0.25 /
&solver scheme='$scheme'$([[ $scheme == collocation ]] && echo ", alpha=$alpha"), target_error=0 /
&output traction_file='$name.trac' /
EON
  "$kcreep" "$name.nml" >/dev/null 2>&1
done <<'EOL'
c05 collocation 0.5 1 1
c00 collocation 0.0 1 1
bw backward 0.5 1 1
e5c collocation 0.5 5 1
e5b backward 0.5 5 1
EOL
gnuplot <<EOG
set terminal pngcairo size 900,560 font ",11"
set output '$out/traction-centre-row.png'
set title "px for xi = 1 along the centre row (unit circle, 40 x 40, nu = 0.25, G = 1)"
set xlabel "x  (leading edge at +1)"
set ylabel "px"
set grid
set key bottom right
plot '< awk ''!/^#/ && \$2==20'' c05.trac' using 3:5 with linespoints pt 7 ps 0.6 title 'collocation alpha = 0.5', \
     '< awk ''!/^#/ && \$2==20'' bw.trac' using 3:5 with linespoints pt 5 ps 0.6 title 'backward (CONTACT-like)', \
     '< awk ''!/^#/ && \$2==20'' c00.trac' using 3:5 with linespoints pt 9 ps 0.6 title 'collocation alpha = 0 (degenerate)'
set terminal pngcairo size 1000,600 font ",11"
set output '$out/elongated-cells-py.png'
set multiplot layout 2,1 title "py for eta = 1, ellipse a/b = 5 on a 40 x 40 grid (cells dx/dy = 5), nu = 0.25"
set xlabel "x"; set ylabel "y"
set cbrange [-40:40]
set palette defined (-40 "blue", 0 "white", 40 "red")
set size ratio 0.3
unset key; unset grid
set title "collocation alpha = 0.5: the traction oscillates in y (verdict 'degenerate')"
plot 'e5c.trac' using 3:4:8 with points pt 5 ps 0.9 lc palette
set title "backward scheme: one sign, as physics demands"
plot 'e5b.trac' using 3:4:8 with points pt 5 ps 0.9 lc palette
unset multiplot
EOG
echo "method_figures.sh: wrote $out/traction-centre-row.png and $out/elongated-cells-py.png"
