#!/usr/bin/env bash
# A one-node Slurm cluster on this machine, for the farm tests and for trying `streyes farm`.
#
#   tools/slurm-local.sh start DIR    installs slurm-wlm and munge when missing (as root), then starts
#                                     munged, slurmctld and slurmd with everything in DIR: a munge key
#                                     of its own, slurm.conf, state, spool, logs, pid files (munge's
#                                     socket alone lives in /run/streyes-munge/); returns once sinfo
#                                     shows the node idle
#   tools/slurm-local.sh stop DIR     cancels the cluster's jobs and stops its daemons (and any job
#                                     step left running) by the process ids in DIR's pid files
#   tools/slurm-local.sh env DIR      prints the line that points Slurm's commands at the cluster:
#                                     export SLURM_CONF=DIR/slurm.conf
#
# The cluster shares nothing with a system Slurm or munge: its own munged socket (slurm.conf's
# AuthInfo), its own ports (free ones, chosen at start), its own node state. `start` first stops
# whatever a previous start in DIR left (daemons still running, or dead ones whose state would
# confuse the next), so a run that was killed never breaks the next. Needs root: slurmd starts jobs
# as their users, and slurmctld runs as SlurmUser=root here.
set -euo pipefail

usage() {
  sed -n '2,17p' "$0" | sed 's/^# \{0,1\}//' >&2
  exit 2
}
[ $# -eq 2 ] || usage
cmd=$1
mkdir -p "$2" 2>/dev/null || { echo "slurm-local: cannot create the folder '$2'" >&2; exit 2; }
DIR=$(cd "$2" && pwd)
CONF=$DIR/slurm.conf
# munged refuses a socket below any folder that not everyone may pass through, and DIR may be in a
# home folder only its owner may enter (root's is mode 700 on a fresh machine): the socket alone
# lives in a folder of /run named after DIR (the rest stays in DIR; munged and slurmd run as root).
SOCKET_DIR=/run/streyes-munge/$(printf '%s' "$DIR" | sha1sum | cut -c1-16)
SOCKET=$SOCKET_DIR/munge.socket

log() { echo "slurm-local: $*" >&2; }

# True while process $1 runs (a zombie, ended but not yet reaped by its parent, does not).
running() {
  local state
  state=$(sed -n 's/^[0-9]* (.*) \([A-Za-z]\) .*/\1/p' "/proc/$1/stat" 2>/dev/null) || return 1
  [ -n "$state" ] && [ "$state" != Z ] && [ "$state" != X ]
}

# A process id from a pid file, when that process runs the program `name`.
live_pid() {
  local file=$1 name=$2 pid
  [ -f "$file" ] || return 1
  pid=$(tr -dc '0-9' <"$file")
  [ -n "$pid" ] && running "$pid" || return 1
  [ "$(cat "/proc/$pid/comm" 2>/dev/null)" = "$name" ] || return 1
  echo "$pid"
}

# Waits up to $2 tenths of a second for process $1 to end.
wait_gone() {
  local pid=$1 n=$2
  while running "$pid" && [ "$n" -gt 0 ]; do sleep 0.1; n=$((n - 1)); done
  ! running "$pid"
}

stop_pid() {
  local pid=$1 what=$2
  kill -TERM "$pid" 2>/dev/null || return 0
  if ! wait_gone "$pid" 100; then
    log "$what (pid $pid) did not stop in 10 s: killing it"
    kill -KILL "$pid" 2>/dev/null || true
    wait_gone "$pid" 50 || true
  fi
}

# Every descendant of process $1, deepest first.
descendants() {
  local p child
  for child in $(ps -o pid= --ppid "$1" 2>/dev/null); do
    descendants "$child"
    echo "$child"
  done
}

# Job steps (slurmstepd) of this cluster that outlived it: they hold its slurmd log open.
stray_stepds() {
  local p
  for p in /proc/[0-9]*; do
    [ "$(cat "$p/comm" 2>/dev/null)" = slurmstepd ] && running "${p#/proc/}" || continue
    if ls -l "$p/fd" 2>/dev/null | grep -q -- "-> $DIR/"; then echo "${p#/proc/}"; fi
  done
}

stop() {
  local pid p
  if pid=$(live_pid "$DIR/slurmctld.pid" slurmctld); then
    # Jobs first, so that no render outlives the cluster (KillWait is 2 s in our slurm.conf).
    SLURM_CONF=$CONF scancel --quiet --full --user="$(id -un)" 2>/dev/null || true
    for _ in $(seq 1 100); do
      [ -z "$(SLURM_CONF=$CONF squeue -h -o %i 2>/dev/null)" ] && break
      sleep 0.1
    done
  fi
  for pid in $(stray_stepds); do
    for p in $(descendants "$pid"); do kill -KILL "$p" 2>/dev/null || true; done
    kill -KILL "$pid" 2>/dev/null || true
  done
  if pid=$(live_pid "$DIR/slurmd.pid" slurmd); then stop_pid "$pid" slurmd; fi
  if pid=$(live_pid "$DIR/slurmctld.pid" slurmctld); then stop_pid "$pid" slurmctld; fi
  if pid=$(live_pid "$DIR/munge/munged.pid" munged); then stop_pid "$pid" munged; fi
  rm -f "$DIR/slurmd.pid" "$DIR/slurmctld.pid" "$DIR/munge/munged.pid"
  rm -rf "$SOCKET_DIR"
  rmdir /run/streyes-munge 2>/dev/null || true
}

free_port() {
  python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])'
}

install_missing() {
  local missing=() p
  for p in slurmctld slurmd sbatch munged mungekey; do
    command -v "$p" >/dev/null || missing+=("$p")
  done
  ((${#missing[@]})) || return 0
  if [ "$(id -u)" -ne 0 ]; then
    log "Slurm and munge are not installed (missing: ${missing[*]}). As root:"
    log "  apt-get update && apt-get install -y slurm-wlm munge"
    exit 1
  fi
  log "installing slurm-wlm and munge"
  apt-get update -qq
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends slurm-wlm munge >/dev/null
}

start() {
  if [ "$(id -u)" -ne 0 ]; then
    log "the local cluster runs its daemons as root: run this as root"
    exit 1
  fi
  install_missing
  stop  # whatever a previous start in DIR left, alive or dead
  rm -rf "$DIR/state" "$DIR/spool" "$DIR/log" "$DIR/munge" "$CONF"
  mkdir -p "$DIR/state" "$DIR/spool" "$DIR/log" "$DIR/munge"
  # munged wants its socket's folder, and every folder above it, open for all to pass through.
  mkdir -p "$SOCKET_DIR"
  chmod 755 /run/streyes-munge "$SOCKET_DIR"

  # munge: a key of this cluster's own (created here, so a missing system key does not matter) and
  # a daemon on a socket of its own.
  mungekey --create --keyfile="$DIR/munge/munge.key"
  munged --socket="$SOCKET" --key-file="$DIR/munge/munge.key" \
         --pid-file="$DIR/munge/munged.pid" --log-file="$DIR/munge/munged.log" \
         --seed-file="$DIR/munge/munged.seed" ||
    { log "munged did not start:"; tail -n 5 "$DIR/munge/munged.log" >&2; exit 1; }

  local host node ctld_port slurmd_port
  host=$(hostname -s)
  # The node as slurmd sees it (CPUs, sockets, cores, memory), so that it registers as configured.
  node=$(slurmd -C | head -n 1)
  [[ $node == NodeName=* ]] || { log "slurmd -C did not describe this node: $node"; exit 1; }
  ctld_port=$(free_port)
  slurmd_port=$(free_port)
  while [ "$slurmd_port" = "$ctld_port" ]; do slurmd_port=$(free_port); done
  cat >"$CONF" <<EOF
# A one-node cluster written by tools/slurm-local.sh; everything it keeps is in $DIR.
ClusterName=streyes
SlurmctldHost=$host
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$SOCKET
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
SchedulerType=sched/backfill
SchedulerParameters=sched_interval=1
AccountingStorageType=accounting_storage/none
JobAcctGatherType=jobacct_gather/none
JobCompType=jobcomp/none
MpiDefault=none
KillWait=2
MinJobAge=600
StateSaveLocation=$DIR/state
SlurmdSpoolDir=$DIR/spool
SlurmctldPidFile=$DIR/slurmctld.pid
SlurmdPidFile=$DIR/slurmd.pid
SlurmctldLogFile=$DIR/log/slurmctld.log
SlurmdLogFile=$DIR/log/slurmd.log
$node State=UNKNOWN
PartitionName=render Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF
  export SLURM_CONF=$CONF
  slurmctld -i || { log "slurmctld did not start:"; tail -n 20 "$DIR/log/slurmctld.log" >&2; stop; exit 1; }
  slurmd || { log "slurmd did not start:"; tail -n 20 "$DIR/log/slurmd.log" >&2; stop; exit 1; }
  local state=""
  for _ in $(seq 1 300); do
    state=$(sinfo -h -n "$host" -o %t 2>/dev/null || true)
    [ "$state" = idle ] && break
    sleep 0.1
  done
  if [ "$state" != idle ]; then
    log "the node is '${state:-unknown}', not idle, 30 s after start. Logs:"
    tail -n 20 "$DIR/log/slurmctld.log" "$DIR/log/slurmd.log" >&2 || true
    stop
    exit 1
  fi
  log "cluster up: node $host idle (slurmctld pid $(cat "$DIR/slurmctld.pid"), slurmd pid $(cat "$DIR/slurmd.pid"), "\
"munged pid $(cat "$DIR/munge/munged.pid")); to use it: export SLURM_CONF=$CONF"
}

case $cmd in
  start) start ;;
  stop) stop; log "cluster in $DIR stopped" ;;
  env) echo "export SLURM_CONF=$CONF" ;;
  *) usage ;;
esac
