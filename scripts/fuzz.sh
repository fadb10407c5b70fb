#!/usr/bin/env bash
# Long fuzz run of kcreep's namelist and mask reader (outside CI; CTest runs
# a 20 s version as the test 'fuzz_short').
#   scripts/fuzz.sh [--duration SECONDS] [--seed N] [--findings DIR]
#   scripts/fuzz.sh --help    this text
# Defaults: 600 s, seed from the clock, findings in fuzz-findings/.
# The binaries are copied first, so rebuilding during the run is harmless.
# Prints how many inputs were tried and what was found; exit 1 on findings.
usage() { awk 'NR > 1 && /^#/ { sub(/^# ?/, ""); print; next } NR > 1 { exit }' "${BASH_SOURCE[0]}"; }
for arg in "$@"; do case $arg in -h | --help) usage; exit 0 ;; --) break ;; esac; done
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build_dir=${KCREEP_BUILD_DIR:-$here/build}
duration=600
seed=$(date +%s)
findings=$PWD/fuzz-findings
while (($#)); do
  case $1 in
    --duration | --seed | --findings)
      (($# >= 2)) || { echo "fuzz.sh: error: $1 needs a value (see --help)" >&2; exit 2; } ;;&
    --duration) duration=$2; shift 2 ;;
    --seed) seed=$2; shift 2 ;;
    --findings) findings=$2; shift 2 ;;
    *) echo "fuzz.sh: error: unknown option '$1' (allowed: --duration S, --seed N, --findings DIR)" >&2; exit 2 ;;
  esac
done
for b in "$build_dir/kcreep" "$build_dir/tests/check_input"; do
  [[ -x $b ]] || { echo "fuzz.sh: error: $b not built (run scripts/setup.sh)" >&2; exit 2; }
done
bin=$(mktemp -d)
trap 'rm -rf "$bin"' EXIT
cp "$build_dir/kcreep" "$build_dir/tests/check_input" "$bin/"
mkdir -p "$findings"
python3 "$here/scripts/fuzz.py" --check "$bin/check_input" --kcreep "$bin/kcreep" \
  --duration "$duration" --seed "$seed" --findings "$findings" --summary "$findings/summary-$seed.json"
