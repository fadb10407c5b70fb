#!/bin/bash
# Error and time of the default run over Kalker's grid of a/b and nu, against
# the refined table (docs/data/kalker_refined.dat); timing under the shared
# benchmark lock. Options go to lab/accuracy_table.py, e.g.
#   lab/accuracy_table.sh --out lab/data/accuracy_default.dat
#   lab/accuracy_table.sh --solver "target_error = 1e-4" --ratios 1
set -euo pipefail
usage() { echo "usage: lab/accuracy_table.sh [options]"; sed -n '2,6p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'; }
for a in "$@"; do [[ $a == -h || $a == --help ]] && { usage; exit 0; }; done
here=$(cd "$(dirname "$0")" && pwd)
export KCREEP=${KCREEP:-$here/../build/kcreep}
exec flock /tmp/kcreep-bench.lock python3 "$here/accuracy_table.py" "$@"
