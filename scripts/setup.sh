#!/usr/bin/env bash
# Set up kcreep on a fresh Debian machine: install the missing packages,
# configure and build (Release) in build/. Safe to run again: it only
# installs what is missing and rebuilds what changed.
#   scripts/setup.sh            packages + build
#   KCREEP_BUILD_DIR=dir        build somewhere else
#   scripts/setup.sh --help     this text (nothing is installed or built)
usage() { awk 'NR > 1 && /^#/ { sub(/^# ?/, ""); print; next } NR > 1 { exit }' "${BASH_SOURCE[0]}"; }
for arg in "$@"; do case $arg in -h | --help) usage; exit 0 ;; --) break ;; esac; done
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build_dir=${KCREEP_BUILD_DIR:-$here/build}

packages=(gfortran gcc cmake make liblapack-dev libopenblas-dev libfftw3-dev gnuplot-nox time python3 python3-numpy python3-scipy python3-matplotlib python3-pip python3-setuptools slurm-wlm munge)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}"
  if [[ $(id -u) -ne 0 ]]; then
    echo "setup: error: packages missing (${missing[*]}) and not root: run as root or install them" >&2
    exit 1
  fi
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

cmake -S "$here" -B "$build_dir" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build_dir" -j "$(nproc)" >/dev/null
echo "setup: built $build_dir/kcreep"
