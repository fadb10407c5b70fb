#!/usr/bin/env bash
# kcreep benchmark: a ladder of grid sizes per solution path, the dgemm and
# dgetrf rates of this machine, and the comparisons of the paths. Prints the table and
# writes docs/performance.md and docs/figures/performance.png.
#   scripts/bench/bench.sh                 full ladder, 3 repeats (medians), ~10 min on 2 cores
#   REPEATS=1 scripts/bench/bench.sh       one run per point
#   QUICK=1 scripts/bench/bench.sh         small sizes only (checks the script, not the numbers)
#   KCREEP_BUILD_DIR=dir             build somewhere else (default build/)
#   scripts/bench/bench.sh --help          this text (nothing is built or run)
source "$(dirname "${BASH_SOURCE[0]}")/../prebuild_lib.sh"
build_kcreep -j "$(nproc)"
exec python3 "$here/scripts/bench/bench.py" "$build_dir" "$here"
