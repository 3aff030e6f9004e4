#!/bin/sh
# A single-node SLURM on this machine, all of its state in one directory:
# for the `cluster` CTest label (tests/cluster_test.sh) and for trying the
# job arrays of tools/slurm/ without a cluster. Needs root (slurmd), Debian's
# slurm-wlm and munge (tools/setup.sh slurm-wlm munge).
#   tools/slurm/local-cluster.sh start DIR   start munged, slurmctld, slurmd;
#                                            prints `export SLURM_CONF=DIR/slurm.conf`
#   tools/slurm/local-cluster.sh stop DIR    stop the three (by their pid files)
# The daemons listen on free ports picked at start, so a cluster of the
# machine's own (/etc/slurm) is left alone.
set -eu
usage() { echo "usage: local-cluster.sh start|stop DIR" >&2; exit 2; }
[ $# -eq 2 ] || usage
cmd=$1 dir=$2

stop() {
  for d in slurmd slurmctld munged; do
    pidfile=$dir/$d.pid
    [ -s "$pidfile" ] || continue
    pid=$(cat "$pidfile")
    kill "$pid" 2>/dev/null || true
    i=0
    while kill -0 "$pid" 2>/dev/null && [ $i -lt 100 ]; do sleep 0.1; i=$((i + 1)); done
    kill -0 "$pid" 2>/dev/null && kill -9 "$pid" 2>/dev/null || true
    rm -f "$pidfile"
  done
}

free_port() {
  python3 -c 'import socket; s = socket.socket(); s.bind(("", 0)); print(s.getsockname()[1])'
}

# Polls `$@` for up to 30 s.
await() {
  what=$1; shift
  i=0
  until "$@" >/dev/null 2>&1; do
    i=$((i + 1))
    if [ $i -gt 300 ]; then echo "local-cluster.sh: $what did not come up (logs in $dir)" >&2; stop; exit 1; fi
    sleep 0.1
  done
}

start() {
  [ "$(id -u)" -eq 0 ] || { echo "local-cluster.sh: slurmd needs root" >&2; exit 2; }
  for p in munged mungekey slurmctld slurmd sinfo; do
    command -v "$p" >/dev/null || [ -x "/usr/sbin/$p" ] ||
      { echo "local-cluster.sh: $p not found (tools/setup.sh slurm-wlm munge)" >&2; exit 2; }
  done
  PATH=$PATH:/usr/sbin
  mkdir -p "$dir/state" "$dir/spool" "$dir/munge"
  dir=$(cd "$dir" && pwd)
  chmod 700 "$dir/munge"
  mungekey --create --keyfile="$dir/munge/munge.key"
  munged --force --key-file="$dir/munge/munge.key" --socket="$dir/munge/munge.socket" \
    --pid-file="$dir/munged.pid" --log-file="$dir/munged.log" --seed-file="$dir/munge/seed"
  await munged munge --socket="$dir/munge/munge.socket" -n
  host=$(hostname -s)
  # The node's real CPUs and memory, as slurmd itself reports them.
  node=$(slurmd -C | head -1 | sed 's/ UpTime=.*//')
  cat >"$dir/slurm.conf" <<CONF
ClusterName=mc1local
SlurmctldHost=$host
SlurmctldPort=$(free_port)
SlurmdPort=$(free_port)
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$dir/munge/munge.socket
CredType=cred/munge
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/slurmctld.log
SlurmdLogFile=$dir/slurmd.log
PlugStackConfig=$dir/plugstack.conf
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
$node State=UNKNOWN
PartitionName=local Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
  : >"$dir/plugstack.conf"
  export SLURM_CONF=$dir/slurm.conf
  slurmctld -f "$SLURM_CONF"
  await slurmctld scontrol ping
  slurmd -f "$SLURM_CONF"
  await "slurmd (node idle)" sh -c "sinfo -h -N -o %t | grep -qx idle"
  echo "export SLURM_CONF=$SLURM_CONF"
}

case $cmd in
  start) start ;;
  stop) stop ;;
  *) usage ;;
esac
