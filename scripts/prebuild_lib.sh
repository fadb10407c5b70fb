#!/usr/bin/env bash
# Shared start of the scripts that build kcreep before they run it
# (bench.sh, bench_normal.sh, bench_preconditioner.sh, figures/normal_figures.sh)
# or time given builds of it (bench_accurate_mode.sh);
# they source it first thing, it is not run on its own.
#   in such a script:  source "$(dirname "${BASH_SOURCE[0]}")/prebuild_lib.sh"
#   scripts/prebuild_lib.sh --help                this text
# Sourced, it answers -h and --help with the comment block at the top of the
# script that sourced it (and exits, nothing built), turns on the options
# "set -euo pipefail", sets "here" (the repository) and "build_dir"
# (KCREEP_BUILD_DIR, default build/ of the repository) and provides
# build_kcreep [cmake --build options]: configure build_dir as a Release
# build and build it, quietly; and median: the median of the numbers on
# standard input, one a line (the benchmarks' statistic).
# (Its name does not start with "build": copies of the tree made by the
# tests leave build* out.)

if [[ ${BASH_SOURCE[0]} == "$0" ]]; then
  case ${1:-} in
    -h | --help) awk 'NR > 1 && /^#/ { sub(/^# ?/, ""); print; next } NR > 1 { exit }' "$0"; exit 0 ;;
    *) echo "prebuild_lib.sh: error: sourced by the scripts that build kcreep, not run (see --help)" >&2; exit 2 ;;
  esac
fi

build_script=${BASH_SOURCE[1]}
usage() { awk 'NR > 1 && /^#/ { sub(/^# ?/, ""); print; next } NR > 1 { exit }' "$build_script"; }
for arg in "$@"; do case $arg in -h | --help) usage; exit 0 ;; --) break ;; esac; done
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build_dir=${KCREEP_BUILD_DIR:-$here/build}

build_kcreep() {
  cmake -S "$here" -B "$build_dir" -DCMAKE_BUILD_TYPE=Release >/dev/null
  cmake --build "$build_dir" "$@" >/dev/null
}

median() { sort -g | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }
