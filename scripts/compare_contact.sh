#!/usr/bin/env bash
# Compare kcreep with Kalker's CONTACT on CONTACT's own contact areas.
#   scripts/compare_contact.sh FILE.out [FILE.out ...]
# For every case of every file: run kcreep with &patch shape = 'contact' (grid,
# mask and material of that case; CONTACT's scheme: backward difference over
# one cell, spin evaluated at x + DX/6), compute FX, FY, MZ for the case's
# creepages and print them beside CONTACT's with the relative difference and
# a one-line verdict. Verdict rule: kcreep agrees when its value rounded to
# the digits CONTACT printed equals CONTACT's value (|difference| <= half a
# unit in CONTACT's last printed digit). Cases with slip (NSLIP > 0) are not
# judged against the linear theory (its full-adhesion forces are only an upper
# bound there); they are compared with kcreep's FASTSIM instead: &fastsim on the
# same grid and pressure (PN of the element file), CONTACT's friction (FKIN of
# the case) and creepages, with the patch's exact L and with the equivalent
# ellipses' L; printed: FASTSIM's FX, FY and |F - F_CONTACT| / (mu FN) in %
# (not judged: FASTSIM is an approximation, see docs/fastsim.md).
# Exit status: 0 all judged cases agree, 1 some differ, 2 a file/case could
# not be read or run (its error is printed).
#   KCREEP=path/to/kcreep   the binary (default: build/kcreep of this checkout)
#   scripts/compare_contact.sh --help   this text
usage() { awk 'NR > 1 && /^#/ { sub(/^# ?/, ""); print; next } NR > 1 { exit }' "${BASH_SOURCE[0]}"; }
for arg in "$@"; do case $arg in -h | --help) usage; exit 0 ;; --) break ;; esac; done
set -uo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
kcreep=${KCREEP:-$here/build/kcreep}
if (($# == 0)); then
  echo "usage: $0 FILE.out [FILE.out ...] (see --help)" >&2
  exit 2
fi
if [[ ! -x $kcreep ]]; then
  echo "compare_contact: error: kcreep binary '$kcreep' not found (build first, or set KCREEP)" >&2
  exit 2
fi
work=$(mktemp -d "${TMPDIR:-/tmp}/compare_contact.XXXXXX")
trap 'rm -rf "$work"' EXIT

# FASTSIM with friction for a case with slip: CONTACT's mu (FKIN of case k), creepages
# (as printed in kcreep's comparison block) and pressure; one line per flexibility source.
fastsim_case() {
  local path=$1 k=$2 block=$3 mu creep cfx cfy
  mu=$(awk -v k="$k" '/FRICTION LAW PARAMETERS/ { n++; if (n == k) { getline; getline; print $2; exit } }' "$path")
  creep=$(sed -n 's/^CONTACT case [0-9]*: CKSI = *\([^,]*\), CETA = *\([^,]*\), CPHI = *\([^;]*\);.*/\1 \2 \3/p' <<<"$block")
  cfx=$(awk '$1 == "CONTACT" && $2 == "FX" { print $3 }' <<<"$block")
  cfy=$(awk '$1 == "CONTACT" && $2 == "FY" { print $3 }' <<<"$block")
  if [[ -z $mu || -z $creep || -z $cfx || -z $cfy ]]; then
    echo "    FASTSIM: not run (friction, creepages or CONTACT's forces not found)"
    return
  fi
  printf "&patch shape = 'contact', contact_file = '%s', contact_case = %d /\n&fastsim mu = %s, creepages = %s,\n  flexibility = 'exact ellipse' /\n&output table_file = '%s', creep_file = '%s' /\n" \
    "${path//\'/\'\'}" "$k" "$mu" "$creep" "$work/fs.tab" "$work/fs.creep" >"$work/fs.nml"
  if ! "$kcreep" "$work/fs.nml" >/dev/null 2>"$work/fs.err"; then
    echo "    FASTSIM: kcreep failed: $(head -n 1 "$work/fs.err")"
    status=2
    return
  fi
  awk -v mu="$mu" -v cfx="$cfx" -v cfy="$cfy" '!/^#/ {
      d = sqrt(($4 - cfx)^2 + ($5 - cfy)^2) / (mu * $7)
      printf "    FASTSIM (mu = %s, L: %s): FX %12.5g  FY %12.5g  |F - F_CONTACT|/(mu FN) = %.2f %%\n", mu, $9, $4, $5, 100 * d
    }' "$work/fs.creep"
}

worst=0
status=0
for out in "$@"; do
  if [[ ! -r $out ]]; then
    echo "compare_contact: error: cannot read '$out'" >&2
    status=2
    continue
  fi
  path=$(cd "$(dirname "$out")" && pwd)/$(basename "$out")
  n_cases=$(grep -c '^ *Case  *[0-9][0-9]* *$' "$path" || true)
  echo "== $(basename "$out"): $n_cases case(s)"
  if ((n_cases == 0)); then
    echo "compare_contact: error: '$out' has no 'Case k' header (not a CONTACT output?)" >&2
    status=2
    continue
  fi
  for ((k = 1; k <= n_cases; k++)); do
    nml=$work/case.nml
    # namelist strings: double any single quote of the path
    printf "&patch shape = 'contact', contact_file = '%s', contact_case = %d /\n&output table_file = '%s' /\n" \
      "${path//\'/\'\'}" "$k" "$work/case.tab" >"$nml"
    if ! result=$("$kcreep" "$nml" 2>"$work/err"); then
      echo "  case $k: kcreep failed: $(head -n 1 "$work/err")"
      status=2
      continue
    fi
    # kcreep's comparison block: the lines that start with 'CONTACT'
    block=$(sed -n 's/^  CONTACT/CONTACT/p' <<<"$result")
    sed -n 's/^CONTACT case/  case/p' <<<"$block"
    sed -n 's/^CONTACT    force/    force/p; s/^CONTACT      \([FM][XYZ]\)/    \1/p' <<<"$block"
    verdict=$(sed -n 's/^CONTACT verdict: //p' <<<"$block")
    echo "    verdict: $verdict"
    case $verdict in
      DIFFERS*) ((status == 0)) && status=1 ;;
    esac
    if [[ $verdict == slip* ]]; then
      fastsim_case "$path" "$k" "$block"
    fi
    # largest relative difference over the judged (no-slip) cases
    if [[ $verdict != slip* ]]; then
      worst=$(awk -v w="$worst" '$1 ~ /^(FX|FY|MZ)$/ && $4 != "-" { r = $4 < 0 ? -$4 : $4; if (r > w) w = r }
                                 END { printf "%.3e", w }' <<<"$(sed -n 's/^CONTACT      //p' <<<"$block")")
    fi
  done
done
echo "largest |relative difference| over the full-adhesion cases: $worst"
exit $status
