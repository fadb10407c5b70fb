#!/usr/bin/env bash
# One task of the job array of run_cases_slurm.sh: kcreep --batch on its
# chunk of cases, writing the chunk's own table. A chunk whose table exists
# is done; a chunk killed before (time-out, node failure, scancel) resumes
# from its .partial table, so no finished case is run twice.
#   sbatch --array=... scripts/slurm/array_task.sh WORKDIR KCREEP
#   scripts/slurm/array_task.sh --help    this text
usage() { awk 'NR > 1 && /^#/ { sub(/^# ?/, ""); print; next } NR > 1 { exit }' "${BASH_SOURCE[0]}"; }
for arg in "$@"; do case $arg in -h | --help) usage; exit 0 ;; --) break ;; esac; done
set -euo pipefail
(($# == 2)) || { echo "array_task.sh: error: needs WORKDIR KCREEP (see --help)" >&2; exit 2; }
workdir=$1
kcreep=$2
chunk=$workdir/chunks/$(printf '%05d' "${SLURM_ARRAY_TASK_ID:?not in a SLURM array task}")

# the BLAS uses the cores SLURM gave this task, no more
export OPENBLAS_NUM_THREADS=${SLURM_CPUS_PER_TASK:-1}
export OMP_NUM_THREADS=${SLURM_CPUS_PER_TASK:-1}

echo "array task $SLURM_ARRAY_TASK_ID on $(hostname -s): $(grep -c . "$chunk.list") cases, $OPENBLAS_NUM_THREADS thread(s)"
if [[ -f $chunk.tab ]]; then
  echo "chunk table $chunk.tab exists: nothing to do"
  exit 0
fi
exec "$kcreep" --batch "$chunk.list" "$chunk.tab"
