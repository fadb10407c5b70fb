#!/bin/bash
# The refined Kalker table (docs/data/kalker_refined.dat), in chunks of at most
# about 5 minutes each (tools/maintenance/refine_kalker_table.py resumes where it stopped).
# Heavy: about an hour on 2 cores for all 57 points; runs under nice.
#   tools/maintenance/refine_kalker_table.sh [extra options of refine_kalker_table.py]
set -euo pipefail
usage() { echo "usage: tools/maintenance/refine_kalker_table.sh [options]"; sed -n '2,5p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'; }
for a in "$@"; do [[ $a == -h || $a == --help ]] && { usage; exit 0; }; done
here=$(cd "$(dirname "$0")" && pwd)
export KCREEP=${KCREEP:-$here/../../build/kcreep}
for chunk in $(seq 1 40); do
  out=$(nice -n 10 python3 "$here/refine_kalker_table.py" --max-seconds 240 "$@" 2>&1 | tee /dev/stderr)
  if ! grep -q "time budget used" <<<"$out"; then break; fi
done
