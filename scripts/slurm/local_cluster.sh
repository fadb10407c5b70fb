#!/usr/bin/env bash
# A one-node SLURM cluster of this machine in a private folder, without
# systemd: for the SLURM test and for trying the cluster scripts locally.
# Needs root (slurmd starts jobs; munged runs as the munge user) and the
# Debian packages slurm-wlm and munge (scripts/setup.sh installs them).
#
#   scripts/slurm/local_cluster.sh start DIR   start munged, slurmctld, slurmd;
#                                              prints: export SLURM_CONF=DIR/slurm.conf
#   scripts/slurm/local_cluster.sh stop DIR    cancel the jobs, stop the daemons
#                                              started in DIR, by their pids
#   scripts/slurm/local_cluster.sh run DIR -- COMMAND...
#                                              start, run COMMAND with SLURM_CONF
#                                              set, stop, and reap the daemons;
#                                              exit with COMMAND's status
#   scripts/slurm/local_cluster.sh --help      this text
#   scripts/slurm/local_cluster.sh check       exit 0 if a cluster can be started
#                                              here, else say why and exit 1
#
# Everything lives in DIR (munge key, socket, pid and log files, slurm.conf,
# state and spool folders); nothing outside it is changed. Ports are free
# ones picked at start. Every wait has a time limit.
#
# The daemons outlive `start` (its shell exits), so they are orphans: their
# parent becomes PID 1, or the nearest child subreaper. Where PID 1 never
# reaps (a container whose first process is not an init), `stop` leaves them
# defunct. `run` avoids that: it makes itself a child subreaper
# (prctl PR_SET_CHILD_SUBREAPER), so the orphaned daemons become its
# children and it reaps them after `stop`. A program that calls start and
# stop itself can do the same (tests/scenario/test_slurm.py does).
usage() { awk 'NR > 1 && /^#/ { sub(/^# ?/, ""); print; next } NR > 1 { exit }' "${BASH_SOURCE[0]}"; }
for arg in "$@"; do case $arg in -h | --help) usage; exit 0 ;; --) break ;; esac; done
set -euo pipefail

bad_usage() { echo "usage: $0 start DIR | stop DIR | run DIR -- COMMAND... | check (see --help)" >&2; exit 2; }
started_dir=
# On an error while starting, stop what was already started.
die() {
  echo "local_cluster: error: $*" >&2
  [[ -z $started_dir ]] || stop "$started_dir"
  exit 1
}

# Why no cluster can be started here (empty when one can).
why_not() {
  local b
  [[ $(id -u) -eq 0 ]] || { echo "not root (slurmd and munged need root)"; return; }
  for b in munged mungekey slurmctld slurmd sbatch squeue scontrol scancel setpriv python3; do
    command -v "$b" >/dev/null 2>&1 || { echo "$b not found (install slurm-wlm and munge: scripts/setup.sh)"; return; }
  done
  id munge >/dev/null 2>&1 || { echo "no munge user (install the munge package)"; return; }
}

# True when pid is alive and runs the program named prog (guards against reused pids).
is_ours() {
  local pid=$1 prog=$2 exe
  [[ -n $pid && -e /proc/$pid ]] || return 1
  exe=$(readlink "/proc/$pid/exe" 2>/dev/null || true)
  [[ $(basename "${exe% (deleted)}") == "$prog"* ]]
}

# Stop one daemon by the pid we recorded: TERM, up to 10 s, then KILL.
stop_pid() {
  local file=$1 prog=$2 pid i
  [[ -f $file ]] || return 0
  pid=$(cat "$file")
  if is_ours "$pid" "$prog"; then
    kill -TERM "$pid" 2>/dev/null || true
    for ((i = 0; i < 100; i++)); do is_ours "$pid" "$prog" || break; sleep 0.1; done
    if is_ours "$pid" "$prog"; then
      echo "local_cluster: $prog ($pid) did not stop on TERM: KILL" >&2
      kill -KILL "$pid" 2>/dev/null || true
    fi
  fi
  rm -f "$file"
}

# Wait up to $1 seconds for the command that follows to succeed.
wait_for() {
  local limit=$1 i
  shift
  for ((i = 0; i < limit * 5; i++)); do
    "$@" >/dev/null 2>&1 && return 0
    sleep 0.2
  done
  return 1
}

free_port() {
  python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])'
}

start() {
  local dir=$1 host cpus mem_mb port_ctld port_d reason
  reason=$(why_not)
  [[ -z $reason ]] || die "$reason"
  [[ ! -e $dir/slurm.conf ]] || die "$dir already holds a cluster (stop it first)"
  mkdir -p "$dir"
  dir=$(cd "$dir" && pwd)
  started_dir=$dir
  chmod 0755 "$dir"
  mkdir -p "$dir/munge" "$dir/state" "$dir/spool" "$dir/log"
  chown munge:munge "$dir/munge"
  chmod 0711 "$dir/munge"   # munged wants its socket folder searchable by all

  # munge: a fresh key, munged as the munge user with its own socket, pid, log and seed
  mungekey --create --keyfile="$dir/munge/munge.key"
  chown munge:munge "$dir/munge/munge.key"
  chmod 0400 "$dir/munge/munge.key"
  setpriv --reuid=munge --regid=munge --init-groups \
    munged --foreground --key-file="$dir/munge/munge.key" --socket="$dir/munge/munge.socket" \
    --pid-file="$dir/munge/munged.pid" --log-file="$dir/munge/munged.log" \
    --seed-file="$dir/munge/munged.seed" </dev/null >"$dir/log/munged.out" 2>&1 &
  echo $! >"$dir/munged.pid"
  wait_for 10 test -S "$dir/munge/munge.socket" ||
    die "munged did not start (see $dir/log/munged.out, $dir/munge/munged.log)"

  host=$(hostname -s)
  cpus=$(nproc)
  mem_mb=$(free -m | awk '/^Mem:/ {print int($2 * 0.9)}')
  port_ctld=$(free_port)
  port_d=$(free_port)
  while [[ $port_d == "$port_ctld" ]]; do port_d=$(free_port); done
  cat >"$dir/slurm.conf" <<EOF
# one-node cluster written by scripts/slurm/local_cluster.sh
ClusterName=kcreeplocal
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$port_ctld
SlurmdPort=$port_d
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$dir/munge/munge.socket
CredType=cred/munge
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.daemon.pid
SlurmdPidFile=$dir/slurmd.daemon.pid
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core_Memory
SchedulerType=sched/backfill
AccountingStorageType=accounting_storage/none
JobAcctGatherType=jobacct_gather/none
JobCompType=jobcomp/none
MpiDefault=none
SwitchType=switch/none
ReturnToService=2
InactiveLimit=0
KillWait=5
MinJobAge=600
NodeName=$host NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=$mem_mb State=UNKNOWN
PartitionName=local Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF
  export SLURM_CONF=$dir/slurm.conf

  slurmctld -D -f "$SLURM_CONF" </dev/null >"$dir/log/slurmctld.out" 2>&1 &
  echo $! >"$dir/slurmctld.pid"
  wait_for 20 scontrol ping ||
    die "slurmctld did not answer (see $dir/log/slurmctld.log, $dir/log/slurmctld.out)"
  slurmd -D -N "$host" -f "$SLURM_CONF" </dev/null >"$dir/log/slurmd.out" 2>&1 &
  echo $! >"$dir/slurmd.pid"
  wait_for 30 node_idle "$host" ||
    die "the node did not become idle (see $dir/log/slurmd.log; sinfo: $(sinfo -h -N -o '%N %T %E' 2>&1))"
  echo "export SLURM_CONF=$SLURM_CONF"
}

node_idle() {
  [[ $(sinfo -h -n "$1" -o %T 2>/dev/null) == idle ]]
}

stop() {
  local dir=$1 pid exe
  [[ -d $dir ]] || return 0
  dir=$(cd "$dir" && pwd)
  export SLURM_CONF=$dir/slurm.conf
  if [[ -f $dir/slurmctld.pid ]] && is_ours "$(cat "$dir/slurmctld.pid")" slurmctld; then
    timeout 20 scancel --full --quiet --user=root 2>/dev/null || true
    wait_for 20 test -z "$(timeout 5 squeue -h -t running,completing -o %i 2>/dev/null)" || true
  fi
  stop_pid "$dir/slurmd.pid" slurmd
  stop_pid "$dir/slurmctld.pid" slurmctld
  # job step daemons of this cluster, if any outlived slurmd: they hold sockets in its spool folder
  for pid in $(ls /proc | grep -E '^[0-9]+$'); do
    exe=$(readlink "/proc/$pid/exe" 2>/dev/null || true)
    [[ $exe == */slurmstepd* ]] || continue
    if tr '\0' '\n' <"/proc/$pid/environ" 2>/dev/null | grep -qxF "SLURM_CONF=$dir/slurm.conf" ||
      ls -l "/proc/$pid/fd" 2>/dev/null | grep -qF "$dir/"; then
      echo "local_cluster: stopping leftover slurmstepd $pid" >&2
      kill -KILL "$pid" 2>/dev/null || true
    fi
  done
  stop_pid "$dir/munged.pid" munged
}

# `run`: the one process that owns the daemons from start to reaping.
run_and_reap='
import ctypes, os, subprocess, sys, time
script, folder, command = sys.argv[1], sys.argv[2], sys.argv[3:]
if ctypes.CDLL(None, use_errno=True).prctl(36, 1, 0, 0, 0) != 0:     # PR_SET_CHILD_SUBREAPER
    sys.exit("local_cluster: run: prctl(PR_SET_CHILD_SUBREAPER) failed: " + os.strerror(ctypes.get_errno()))

def reap(limit):   # reap every child that ends within limit seconds (the stopped daemons)
    end = time.time() + limit
    while time.time() < end:
        try:
            pid, _ = os.waitpid(-1, os.WNOHANG)
        except ChildProcessError:
            return
        if pid == 0:
            time.sleep(0.1)

start = subprocess.run([script, "start", folder])
rc = 1
if start.returncode == 0:
    env = dict(os.environ, SLURM_CONF=os.path.join(os.path.abspath(folder), "slurm.conf"))
    try:
        rc = subprocess.run(command, env=env).returncode
    except OSError as e:
        print(f"local_cluster: run: cannot run {command[0]}: {e}", file=sys.stderr)
        rc = 127
    stop = subprocess.run([script, "stop", folder])
    rc = rc if stop.returncode == 0 else (rc or 1)
reap(15)
sys.exit(rc)
'

case ${1:-} in
  start) [[ $# -eq 2 ]] || bad_usage; start "$2" ;;
  stop) [[ $# -eq 2 ]] || bad_usage; stop "$2" ;;
  run)
    [[ $# -ge 4 && $3 == -- ]] || bad_usage
    # python3 for prctl: a subreaper that starts, runs, stops and reaps in one process
    exec python3 -c "$run_and_reap" "${BASH_SOURCE[0]}" "$2" "${@:4}" ;;
  check)
    reason=$(why_not)
    [[ -z $reason ]] || { echo "local_cluster: cannot start a cluster here: $reason" >&2; exit 1; }
    ;;
  *) bad_usage ;;
esac
