#!/usr/bin/env bash
# kcreep's numerical-stability suite: stiff and extreme cases, each judged
# stable / degraded / fails (rules in scripts/stability.py), plus a comparison
# of the refinement modes on the stiff ones. Writes docs/stability.md (the
# hand-written head is kept, the tables after '## Cases' are regenerated) and
# docs/stability.tab (one line per case, '|'-separated).
#   scripts/stability.sh            full suite (a few minutes; grids up to 120 x 120, ~4 GB)
#   scripts/stability.sh --quick    the subset CTest runs (stability_quick), report to stdout only
#   scripts/stability.sh --help     this text
# Exit 1 when a case fails.
usage() { awk 'NR > 1 && /^#/ { sub(/^# ?/, ""); print; next } NR > 1 { exit }' "${BASH_SOURCE[0]}"; }
for arg in "$@"; do case $arg in -h | --help) usage; exit 0 ;; --) break ;; esac; done
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build_dir=${KCREEP_BUILD_DIR:-$here/build}
[[ -x $build_dir/kcreep ]] || { echo "stability.sh: error: $build_dir/kcreep not built (run scripts/setup.sh)" >&2; exit 2; }
case ${1:-} in
  --quick) exec python3 "$here/scripts/stability.py" --kcreep "$build_dir/kcreep" --quick ;;
  "") exec python3 "$here/scripts/stability.py" --kcreep "$build_dir/kcreep" --refine-compare \
        --markdown "$here/docs/stability.md" --table "$here/docs/stability.tab" ;;
  *) echo "stability.sh: error: unknown option '$1' (allowed: --quick)" >&2; exit 2 ;;
esac
