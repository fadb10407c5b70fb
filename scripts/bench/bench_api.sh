#!/usr/bin/env bash
# The in-loop cost: a 40 x 40 ellipse and a 40 x 40 mask solved through the
# C API and through Python (first call, then the median of repeated calls on
# one handle), against the command-line process per case. Prints the table
# and writes the "api" section of docs/performance.md.
#   scripts/bench/bench_api.sh [--repeats N] [--no-docs]
#   scripts/bench/bench_api.sh --help
set -euo pipefail
usage() { sed -n '2,7p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'; }
for a in "$@"; do [[ $a == -h || $a == --help ]] && { usage; exit 0; }; done
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
build_dir=${KCREEP_BUILD_DIR:-$here/build}
cmake -S "$here" -B "$build_dir" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build_dir" -j "$(nproc)" >/dev/null
# one benchmark at a time on a shared machine
exec flock /tmp/kcreep-bench.lock /usr/bin/python3 "$here/scripts/bench/bench_api.py" "$build_dir" "$here" "$@"
