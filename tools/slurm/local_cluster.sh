#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# A single-node Slurm cluster on localhost, for trying the campaign array job
# (tools/slurm/campaign.sbatch) without a real cluster. Debian's slurm-wlm and
# munge; no systemd needed: the daemons are started directly, as daemons.
#
# Usage: tools/slurm/local_cluster.sh start|stop|status|env
#   start   generate a munge key (once) and slurm.conf into the state dir, start
#           munged, slurmctld and slurmd, wait until the node is idle
#   stop    stop slurmd, slurmctld and munged; nothing of the cluster keeps running
#   status  the daemons' state and `sinfo`
#   env     print `export SLURM_CONF=...`: eval "$(tools/slurm/local_cluster.sh env)"
#           makes sbatch, squeue, scontrol talk to this cluster
#
# State dir: build/slurm-local (LADRC_SLURM_STATE overrides it); it holds the munge
# key, slurm.conf, the controller's state, slurmd's spool and the logs. The munge
# socket lives in /tmp/ladrc-munge-<uid>-<checksum of the state dir>: munged wants
# every directory above it open to all, which a checkout's path need not be.
# Ports: LADRC_SLURM_PORT (controller, default 6817) and the next one (slurmd).
# Run as root (SlurmUser=root, the jobs run as the submitting user).
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
state=${LADRC_SLURM_STATE:-$root/build/slurm-local}
port=${LADRC_SLURM_PORT:-6817}
conf=$state/slurm.conf
munge_run=/tmp/ladrc-munge-$(id -u)-$(printf '%s' "$state" | cksum | cut -d' ' -f1)
munge_socket=$munge_run/munge.socket
# How long `start` waits for the node to come up (daemon start-up, not a test timeout).
start_wait_s=${LADRC_SLURM_START_WAIT_S:-60}

usage() { sed -n '3,20s/^# \{0,1\}//p' "$0"; }
die() { echo "local_cluster.sh: error: $*" >&2; exit 1; }

pid_alive() { [[ -s $1 ]] && kill -0 "$(cat "$1")" 2>/dev/null; }

# Stops the daemon of a pid file: TERM, then KILL if it is still there after 10 s.
stop_pid() { # name pidfile
  local pid i
  [[ -s $2 ]] || return 0
  pid=$(cat "$2")
  if kill -0 "$pid" 2>/dev/null; then
    kill -TERM "$pid" 2>/dev/null || true
    for ((i = 0; i < 100; i++)); do
      kill -0 "$pid" 2>/dev/null || break
      sleep 0.1
    done
    if kill -0 "$pid" 2>/dev/null; then
      echo "local_cluster.sh: $1 (pid $pid) ignored TERM, killing it" >&2
      kill -KILL "$pid" 2>/dev/null || true
    fi
    echo "stopped $1 (pid $pid)"
  fi
  rm -f "$2"
}

write_conf() {
  local cpus mem_mib
  # slurmd -C reports what slurmd will find; a node configured with more CPUs or
  # memory than that is drained as "invalid".
  cpus=$(slurmd -C | sed -n 's/.*CPUs=\([0-9]*\).*/\1/p')
  mem_mib=$(slurmd -C | sed -n 's/.*RealMemory=\([0-9]*\).*/\1/p')
  [[ -n $cpus && -n $mem_mib ]] || die "slurmd -C did not report CPUs and RealMemory"
  cat >"$conf" <<EOF
# Written by tools/slurm/local_cluster.sh: a single-node cluster on localhost.
ClusterName=ladrc-local
SlurmctldHost=localhost
SlurmctldPort=$port
SlurmdPort=$((port + 1))
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$munge_socket
StateSaveLocation=$state/ctld
SlurmdSpoolDir=$state/spool
SlurmctldPidFile=$state/run/slurmctld.pid
SlurmdPidFile=$state/run/slurmd.pid
SlurmctldLogFile=$state/log/slurmctld.log
SlurmdLogFile=$state/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SchedulerType=sched/backfill
SwitchType=switch/none
MpiDefault=none
JobCompType=jobcomp/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
ReturnToService=2
SlurmctldTimeout=30
SlurmdTimeout=30
MaxArraySize=100001
NodeName=localhost NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=$mem_mib State=UNKNOWN
PartitionName=local Nodes=localhost Default=YES MaxTime=INFINITE State=UP
EOF
}

node_state() { SLURM_CONF=$conf sinfo -h -N -n localhost -o '%T' 2>/dev/null | head -n 1; }

start() {
  for tool in munged mungekey slurmctld slurmd sinfo scontrol; do
    command -v "$tool" >/dev/null 2>&1 || die "$tool not found (apt-get install slurm-wlm munge)"
  done
  [[ $(id -u) -eq 0 ]] || die "run as root (the cluster runs its daemons and jobs as root)"
  mkdir -p "$state"/{munge,ctld,spool,run,log}
  # munged refuses a socket dir that not everyone may enter ("Socket is inaccessible"),
  # and a key, log or socket dir that others may write.
  chmod 755 "$state/munge"
  mkdir -p "$munge_run"
  chmod 755 "$munge_run"

  if [[ ! -s $state/munge/munge.key ]]; then
    mungekey --create --keyfile="$state/munge/munge.key"
    echo "generated munge key $state/munge/munge.key"
  fi
  chmod 600 "$state/munge/munge.key"
  if pid_alive "$state/run/munged.pid"; then
    echo "munged already running (pid $(cat "$state/run/munged.pid"))"
  else
    munged --socket="$munge_socket" --key-file="$state/munge/munge.key" \
      --pid-file="$state/run/munged.pid" --log-file="$state/log/munged.log" \
      --seed-file="$state/munge/munged.seed" ||
      die "munged did not start (see $state/log/munged.log)"
    echo "started munged (pid $(cat "$state/run/munged.pid"))"
  fi
  munge -S "$munge_socket" -n | unmunge -S "$munge_socket" >/dev/null ||
    die "munge credentials do not round-trip through $munge_socket"

  write_conf
  export SLURM_CONF=$conf
  if pid_alive "$state/run/slurmctld.pid"; then
    echo "slurmctld already running (pid $(cat "$state/run/slurmctld.pid"))"
  else
    # -c: a clean start, no jobs or node state from an earlier cluster.
    slurmctld -c -f "$conf" || die "slurmctld did not start (see $state/log/slurmctld.log)"
    echo "started slurmctld"
  fi
  if pid_alive "$state/run/slurmd.pid"; then
    echo "slurmd already running (pid $(cat "$state/run/slurmd.pid"))"
  else
    # -N: the node's name in slurm.conf, not the machine's host name.
    slurmd -N localhost -f "$conf" || die "slurmd did not start (see $state/log/slurmd.log)"
    echo "started slurmd"
  fi

  local i s=""
  for ((i = 0; i < start_wait_s * 2; i++)); do
    s=$(node_state || true)
    case $s in
      idle | mixed | allocated) break ;;
    esac
    sleep 0.5
  done
  case $s in
    idle | mixed | allocated) ;;
    *)
      tail -n 20 "$state/log/slurmctld.log" "$state/log/slurmd.log" >&2 || true
      die "node localhost is '${s:-unknown}' after ${start_wait_s} s, not idle"
      ;;
  esac
  echo "cluster up: node localhost $s (SLURM_CONF=$conf)"
}

stop() {
  local i
  # Jobs still running would outlive slurmd (their slurmstepd and tasks): cancel them and
  # wait until the controller has none left (up to 30 s) before stopping the daemons.
  if pid_alive "$state/run/slurmctld.pid" && [[ -n $(SLURM_CONF=$conf squeue -h -o %i 2>/dev/null) ]]; then
    echo "cancelling the cluster's jobs: $(SLURM_CONF=$conf squeue -h -o %i | tr '\n' ' ')"
    SLURM_CONF=$conf scancel --full --user="$(id -un)" 2>/dev/null || true
    for ((i = 0; i < 300; i++)); do
      [[ -z $(SLURM_CONF=$conf squeue -h -o %i 2>/dev/null) ]] && break
      sleep 0.1
    done
    [[ -z $(SLURM_CONF=$conf squeue -h -o %i 2>/dev/null) ]] ||
      echo "local_cluster.sh: jobs still listed after 30 s: $(SLURM_CONF=$conf squeue -h -o '%i %T' | tr '\n' ' ')" >&2
  fi
  stop_pid slurmd "$state/run/slurmd.pid"
  stop_pid slurmctld "$state/run/slurmctld.pid"
  stop_pid munged "$state/run/munged.pid"
  rmdir "$munge_run" 2>/dev/null || true # gone with munged's socket, unless another user's
}

status() {
  local rc=0 d
  for d in munged slurmctld slurmd; do
    if pid_alive "$state/run/$d.pid"; then
      echo "$d: running (pid $(cat "$state/run/$d.pid"))"
    else
      echo "$d: not running"
      rc=3
    fi
  done
  if [[ $rc -eq 0 ]]; then
    SLURM_CONF=$conf sinfo -N -l || rc=3
  fi
  return $rc
}

case ${1:-} in
  start) start ;;
  stop) stop ;;
  status) status ;;
  env) echo "export SLURM_CONF=$(printf '%q' "$conf")" ;;
  -h | --help) usage ;;
  *) usage >&2; exit 2 ;;
esac
