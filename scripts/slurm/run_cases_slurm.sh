#!/usr/bin/env bash
# Run the cases of a list on SLURM: a job array whose tasks each run
# `kcreep --batch` on a chunk of the cases, and a gather job (after the whole
# array, whatever became of it) that merges the chunk tables into OUT_TABLE,
# checks that every case is there exactly once and names the missing ones.
#
#   scripts/slurm/run_cases_slurm.sh LIST OUT_TABLE [options]
#   scripts/slurm/run_cases_slurm.sh --help
#
# LIST: one namelist path per line, relative to LIST's folder; blank lines
# and lines starting with # are skipped (as for kcreep --batch).
# One table holds one kind: single patches, or contact tables (&wheel_rail:
# each task writes their <name>.wr in this folder, the jobs' working folder,
# and the table holds their rows); a list mixing them is refused.
#
# Options (defaults in brackets):
#   --partition P       partition [the cluster's default]
#   --cpus-per-task N   cores per array task; OPENBLAS_NUM_THREADS and
#                       OMP_NUM_THREADS follow it [1]
#   --mem MB            memory per array task in MB [the largest
#                       `kcreep --estimate-memory` of the cases to run,
#                       plus 64 MiB for the program, plus 10 %]
#   --time T            time limit per array task [01:00:00]
#   --chunk K           cases per array task [ceil(cases / 100): at most 100 tasks]
#   --max-running M     at most M array tasks at once (--array=...%M) [no limit]
#   --workdir DIR       state of the sweep [OUT_TABLE.slurm]
#   --kcreep PATH       the kcreep binary, visible from the compute nodes
#                       [$KCREEP, else build/kcreep of this repository]
#   --job-name NAME     [kcreep]
#   --sbatch-arg ARG    one more argument for the array's sbatch (repeat it;
#                       e.g. --sbatch-arg=--account=proj --sbatch-arg=--hold)
#   --retry-failed      run again the chunks with failed cases (rows with
#                       verdict error:..., e.g. a node short of memory); their
#                       old tables are kept as NNNNN.tab.failed
#   --wait              wait for the gather job; exit with its status
#
# Restart: run the same command again. Chunks whose table exists are not
# resubmitted; a chunk that was killed (time-out, node failure, scancel)
# resumes after its last finished case (its kcreep --batch .partial table).
# Unless the input fingerprint of one of its cases changed since it was
# submitted (`kcreep --fingerprint`: the program, the namelist and every file
# it reads, by content; the rule of kcreep --batch and run_cases.sh): then
# the chunk runs again from the start (its old table is kept as
# NNNNN.tab.stale).
# When every chunk is done, the gather runs at once, here, without SLURM.
#
# Exit status: 0 submitted (with --wait: 0 table complete, 5 complete with
# failed cases, 1 cases missing), 2 usage or input error, 3 sbatch failed.
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
repo=$(cd "$here/../.." && pwd)

die() { echo "run_cases_slurm: error: $*" >&2; exit "${2:-2}"; }
usage() { awk 'NR > 1 && /^#/ { sub(/^# ?/, ""); print; next } NR > 1 { exit }' "${BASH_SOURCE[0]}"; }

partition= cpus=1 mem_mb= time_limit=01:00:00 chunk= max_running= workdir= wait=0
kcreep=${KCREEP:-$repo/build/kcreep} job_name=kcreep retry_failed=0
extra=()
positional=()
while (($#)); do
  case $1 in
    --partition=*) partition=${1#*=} ;;
    --partition) partition=${2:?--partition needs a value}; shift ;;
    --cpus-per-task=*) cpus=${1#*=} ;;
    --cpus-per-task) cpus=${2:?--cpus-per-task needs a value}; shift ;;
    --mem=*) mem_mb=${1#*=} ;;
    --mem) mem_mb=${2:?--mem needs a value}; shift ;;
    --time=*) time_limit=${1#*=} ;;
    --time) time_limit=${2:?--time needs a value}; shift ;;
    --chunk=*) chunk=${1#*=} ;;
    --chunk) chunk=${2:?--chunk needs a value}; shift ;;
    --max-running=*) max_running=${1#*=} ;;
    --max-running) max_running=${2:?--max-running needs a value}; shift ;;
    --workdir=*) workdir=${1#*=} ;;
    --workdir) workdir=${2:?--workdir needs a value}; shift ;;
    --kcreep=*) kcreep=${1#*=} ;;
    --kcreep) kcreep=${2:?--kcreep needs a value}; shift ;;
    --job-name=*) job_name=${1#*=} ;;
    --job-name) job_name=${2:?--job-name needs a value}; shift ;;
    --sbatch-arg=*) extra+=("${1#*=}") ;;
    --sbatch-arg) extra+=("${2:?--sbatch-arg needs a value}"); shift ;;
    --wait) wait=1 ;;
    --retry-failed) retry_failed=1 ;;
    -h | --help) usage; exit 0 ;;
    -*) die "unknown option $1 (see --help)" ;;
    *) positional+=("$1") ;;
  esac
  shift
done
((${#positional[@]} == 2)) || die "usage: run_cases_slurm.sh LIST OUT_TABLE [options] (see --help)"
list=${positional[0]}
out=${positional[1]}
[[ -f $list && -r $list ]] || die "list '$list': cannot read it"
[[ $cpus =~ ^[1-9][0-9]*$ ]] || die "--cpus-per-task '$cpus': a positive integer"
[[ -z $mem_mb || $mem_mb =~ ^[1-9][0-9]*$ ]] || die "--mem '$mem_mb': a positive integer (MB)"
[[ -z $chunk || $chunk =~ ^[1-9][0-9]*$ ]] || die "--chunk '$chunk': a positive integer"
[[ -z $max_running || $max_running =~ ^[1-9][0-9]*$ ]] || die "--max-running '$max_running': a positive integer"
[[ -x $kcreep ]] || die "kcreep binary '$kcreep' not found or not executable (build it, or --kcreep PATH)"
kcreep=$(cd "$(dirname "$kcreep")" && pwd)/$(basename "$kcreep")
out_dir=$(cd "$(dirname "$out")" 2>/dev/null && pwd) || die "OUT_TABLE '$out': its folder does not exist"
out=$out_dir/$(basename "$out")
workdir=${workdir:-$out.slurm}
command -v sbatch >/dev/null || die "sbatch not found: is this a SLURM submit host?"

# the cases, as absolute paths, in list order
list_dir=$(cd "$(dirname "$list")" && pwd)
cases_new=$(mktemp)
trap 'rm -f "$cases_new"' EXIT
while IFS= read -r line || [[ -n $line ]]; do
  line=${line#"${line%%[![:space:]]*}"}
  line=${line%"${line##*[![:space:]]}"}
  [[ -z $line || $line == \#* ]] && continue
  [[ $line == /* ]] || line=$list_dir/$line
  printf '%s\n' "$line"
done <"$list" >"$cases_new"
n_cases=$(wc -l <"$cases_new")
((n_cases > 0)) || die "list '$list': no cases"
# one table holds one kind (kcreep --batch's rule, over the whole list: the
# chunks must agree); contact tables (&wheel_rail) write <name>.wr in the tasks'
# working folder, this one: two cases of one name would write the same file
is_table() { [[ -r $1 ]] && sed 's/!.*//' "$1" | grep -qiE '(^|[^[:alnum:]_])&wheel_rail([^[:alnum:]_]|$)'; }
n_tables=0 n_patches=0 table_names=()
while IFS= read -r path; do
  if is_table "$path"; then
    n_tables=$((n_tables + 1)) name=${path##*/} && table_names+=("${name%.*}")
  elif [[ -r $path ]]; then
    n_patches=$((n_patches + 1))
  fi
done <"$cases_new"
((n_tables == 0 || n_patches == 0)) ||
  die "list '$list': $n_tables contact tables (&wheel_rail) and $n_patches single patches: one table holds one kind (give each kind its own list)"
twice=$(printf '%s\n' "${table_names[@]}" | sort | uniq -d | head -n 1)
[[ -z $twice ]] || die "list '$list': two contact tables named '$twice' would both write $PWD/$twice.wr (rename one)"
chunk=${chunk:-$(((n_cases + 99) / 100))}
n_chunks=$(((n_cases + chunk - 1) / chunk))

# the sweep's folder: new, or the same sweep again (restart)
mkdir -p "$workdir/chunks" "$workdir/logs"
workdir=$(cd "$workdir" && pwd)
if [[ -f $workdir/cases.list ]]; then
  cmp -s "$workdir/cases.list" "$cases_new" && [[ $(cat "$workdir/chunk_size") == "$chunk" ]] ||
    die "$workdir holds another sweep (other cases or chunk size); remove it or choose --workdir"
  if [[ -s $workdir/jobs ]]; then
    active=$(squeue -h -o %F 2>/dev/null | sort -u | grep -xFf "$workdir/jobs" | paste -sd, || true)
    [[ -z $active ]] || die "jobs $active of this sweep are still queued or running; wait for them or scancel them"
  fi
else
  cp "$cases_new" "$workdir/cases.list"
  echo "$chunk" >"$workdir/chunk_size"
  # the gathered table names each case relative to the list's folder, as kcreep --batch does
  printf '%s\n' "$list_dir" >"$workdir/list_dir"
  split -l "$chunk" -a 5 --numeric-suffixes=1 --additional-suffix=.list "$workdir/cases.list" "$workdir/chunks/"
fi

# The input fingerprint of each case (kcreep --fingerprint); a chunk whose
# cases' fingerprints changed since it was submitted is stale.
mapfile -t stamps < <(xargs -d '\n' "$kcreep" --fingerprint <"$workdir/cases.list" | cut -d' ' -f1)
((${#stamps[@]} == n_cases)) || die "could not fingerprint the inputs of the cases (kcreep --fingerprint failed)"
chunk_stamp() { printf '%s\n' "${stamps[@]:$((($1 - 1) * chunk)):$chunk}" | sha256sum | cut -d' ' -f1; }

# chunks still to run
pending=()
for ((i = 1; i <= n_chunks; i++)); do
  table=$workdir/chunks/$(printf '%05d' "$i").tab
  stamp=$(chunk_stamp "$i")
  if [[ -f $table || -f $table.partial ]] && [[ ! -f ${table%.tab}.stamp || $(<"${table%.tab}.stamp") != "$stamp" ]]; then
    echo "run_cases_slurm: chunk $i: its cases' inputs changed since it ran; running it again"
    [[ ! -f $table ]] || mv "$table" "$table.stale"
    rm -f "$table.partial"
  fi
  if ((retry_failed)) && [[ -f $table ]] && awk '/^#/ {for (i = 2; i <= NF; i++) if ($i == "verdict") col = i - 1; next}
      col && $col ~ /^error:/ {found = 1} END {exit !found}' "$table"; then
    mv "$table" "$table.failed"
  fi
  if [[ ! -f $table ]]; then
    pending+=("$i")
    echo "$stamp" >"${table%.tab}.stamp"
  fi
done
if ((${#pending[@]} == 0)); then
  echo "run_cases_slurm: all $n_chunks chunk(s) done already: gathering here"
  exec python3 "$here/gather.py" "$workdir" "$out"
fi

# memory per task: the largest need among the cases still to run
if [[ -z $mem_mb ]]; then
  todo=$(mktemp)
  for i in "${pending[@]}"; do cat "$workdir/chunks/$(printf '%05d' "$i").list"; done >"$todo"
  max_bytes=0
  while IFS= read -r path; do
    # a case kcreep cannot read gets an error row in its task; it needs no memory
    # 'FILE BYTES PATH': the bytes are the last field but one
    # with the task's CPUs, not this host's: a contact table counts a shift per CPU at once
    bytes=$(OMP_NUM_THREADS=$cpus "$kcreep" --estimate-memory "$path" 2>/dev/null | awk '{print $(NF - 1)}') &&
      [[ -n $bytes ]] || continue
    ((bytes > max_bytes)) && max_bytes=$bytes
  done <"$todo"
  rm -f "$todo"
  mem_mb=$(((max_bytes + 64 * 1048576) * 11 / 10 / 1000000 + 1))
fi

array_spec=$(IFS=,; echo "${pending[*]}")
[[ -z $max_running ]] || array_spec+="%$max_running"
common=(--parsable --job-name="$job_name")
[[ -z $partition ]] || common+=(--partition="$partition")

array_id=$(sbatch "${common[@]}" --array="$array_spec" --cpus-per-task="$cpus" --mem="$mem_mb" \
  --time="$time_limit" --output="$workdir/logs/task_%a_%A.out" --chdir="$workdir" "${extra[@]}" \
  "$here/array_task.sh" "$workdir" "$kcreep") || die "sbatch of the job array failed" 3
array_id=${array_id%%;*}
echo "$array_id" >>"$workdir/jobs"

rm -f "$workdir/gather.exit"
gather_id=$(sbatch "${common[@]}" --job-name="$job_name-gather" --dependency="afterany:$array_id" \
  --kill-on-invalid-dep=no --cpus-per-task=1 --mem=500 --time=00:30:00 \
  --output="$workdir/logs/gather_%j.out" --chdir="$workdir" \
  --wrap="$(printf 'exec python3 %q %q %q' "$here/gather.py" "$workdir" "$out")") \
  || die "sbatch of the gather job failed" 3
# (--wrap: sbatch copies a script it is given to its spool folder, where
#  gather.py would not find the kcreep.table module beside the repository)
gather_id=${gather_id%%;*}
echo "$gather_id" >>"$workdir/jobs"
echo "run_cases_slurm: $n_cases cases in $n_chunks chunk(s) of $chunk; submitted ${#pending[@]} array task(s):" \
  "job $array_id (--cpus-per-task=$cpus --mem=${mem_mb}M --time=$time_limit)"
echo "run_cases_slurm: gather job $gather_id writes $out (log: $workdir/logs/gather_${gather_id}.out)"
echo "run_cases_slurm: array job $array_id gather job $gather_id"
((wait)) || exit 0

# --wait: poll every second (sbatch --wait backs off to half a minute between polls)
failures=0
while [[ ! -f $workdir/gather.exit ]]; do
  if ! state=$(squeue -h -j "$gather_id" -t all -o %T 2>/dev/null); then
    # slurmctld busy, or the job already purged from its memory
    ((++failures < 30)) || break
  else
    failures=0
    case $state in
      PENDING | RUNNING | COMPLETING | CONFIGURING | SUSPENDED | REQUEUE* | RESIZING | STAGE_OUT | SIGNALING) ;;
      *) sleep 1; [[ -f $workdir/gather.exit ]] || break ;;   # ended: allow its file a second to appear
    esac
  fi
  sleep 1
done
cat "$workdir/logs/gather_${gather_id}.out" 2>/dev/null || true
[[ -f $workdir/gather.exit ]] || die "the gather job $gather_id ended without a result (see its log)" 1
exit "$(cat "$workdir/gather.exit")"
