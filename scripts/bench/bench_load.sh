#!/usr/bin/env bash
# kcreep on a busy machine: the README example, input/crescent.nml, 128 and
# 280 x 280 iterative solves, a --batch of 20 ellipses, &rolling, a wheel/rail
# table with &rolling, each alone and beside N busy processes (N = CPUs),
# default threads against OMP_NUM_THREADS=1. Prints the table and writes the
# "load" section of docs/performance.md (not with --only TEXT: those runs only).
#   scripts/bench/bench_load.sh [--repeats R] [--no-docs] [--only TEXT]
#   scripts/bench/bench_load.sh --help
set -euo pipefail
usage() { sed -n '2,8p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'; }
for a in "$@"; do [[ $a == -h || $a == --help ]] && { usage; exit 0; }; done
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
build_dir=${KCREEP_BUILD_DIR:-$here/build}
cmake -S "$here" -B "$build_dir" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build_dir" -j "$(nproc)" >/dev/null
# one benchmark at a time on a shared machine
exec flock /tmp/kcreep-bench.lock python3 "$here/scripts/bench/bench_load.py" "$build_dir" "$here" "$@"
