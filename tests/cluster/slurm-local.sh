#!/usr/bin/env bash
# A single-node SLURM cluster on this machine, for the cluster test (tests/cluster/test_slurm.py) and CI.
#
#   tests/cluster/slurm-local.sh up      # start munged, slurmctld, slurmd; wait until the node is idle
#   tests/cluster/slurm-local.sh down    # cancel its jobs, stop the three daemons, remove its folder
#   tests/cluster/slurm-local.sh status  # exit 0 when its node answers and is usable
#   tests/cluster/slurm-local.sh env     # print the SLURM_CONF line the client commands need
#
# Everything lives in one folder ($WORKBENCH_SLURM_DIR, default /tmp/workbench-slurm): its own munge key
# and socket, slurm.conf, state, spool, pid and log files, so it touches neither /etc nor a site SLURM.
# Ports: slurmctld $WORKBENCH_SLURM_PORT (default 16817), slurmd the next one (a system SLURM uses 6817/6818),
# so two such clusters (two test sessions) can run side by side. Needs root (slurmd and munged run as root here)
# and the Debian packages slurm-wlm and munge (.ci/slurm-up installs them). Node size (CPUs, memory) and
# host name are read at run time. The SLURM client commands find this cluster through SLURM_CONF.
set -euo pipefail

D=${WORKBENCH_SLURM_DIR:-/tmp/workbench-slurm}
CONF=$D/slurm.conf
PORT=${WORKBENCH_SLURM_PORT:-16817}
export SLURM_CONF=$CONF

die() { echo "slurm-local: $*" >&2; exit 1; }

node_state() { sinfo -h -N -o '%T' 2>/dev/null | head -1; }

status() {
  [ -f "$CONF" ] || return 1
  local s
  s=$(timeout 10 sinfo -h -N -o '%T' 2>/dev/null | head -1) || return 1
  case "$s" in idle|mixed|allocated|completing) return 0 ;; *) return 1 ;; esac
}

write_conf() {
  local host cpus mem
  host=$(hostname -s)
  cpus=$(nproc)
  mem=$(awk '/^MemTotal:/ {printf "%d", $2 / 1024 * 0.9}' /proc/meminfo)  # MB, a margin below the real size
  cat > "$CONF" <<CONF
# written by tests/cluster/slurm-local.sh (a single-node test cluster)
ClusterName=workbench-local
SlurmctldHost=$host
SlurmctldPort=$PORT
SlurmdPort=$((PORT + 1))
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$D/munge/munge.socket
CredType=cred/munge
StateSaveLocation=$D/state
SlurmdSpoolDir=$D/spool
SlurmctldPidFile=$D/slurmctld.pid
SlurmdPidFile=$D/slurmd.pid
SlurmctldLogFile=$D/log/slurmctld.log
SlurmdLogFile=$D/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
MpiDefault=none
JobAcctGatherType=jobacct_gather/none
SlurmctldTimeout=30
SlurmdTimeout=30
InactiveLimit=0
KillWait=5
MinJobAge=30
NodeName=$host CPUs=$cpus RealMemory=$mem State=UNKNOWN
PartitionName=debug Nodes=$host Default=YES MaxTime=INFINITE State=UP OverSubscribe=FORCE:4
CONF
}

up() {
  [ "$(id -u)" = 0 ] || die "needs root (slurmd and munged run as root in this test setup)"
  for b in munged slurmctld slurmd sinfo sbatch; do
    command -v "$b" >/dev/null 2>&1 || [ -x "/usr/sbin/$b" ] || die "$b not found (apt-get install slurm-wlm munge)"
  done
  export PATH=$PATH:/usr/sbin
  if status; then echo "slurm-local: already up ($CONF)"; return 0; fi
  mkdir -p "$D"/munge "$D"/state "$D"/spool "$D"/log
  chmod 700 "$D" "$D"/munge
  if [ ! -f "$D/munge/munge.key" ]; then
    dd if=/dev/urandom bs=1 count=1024 of="$D/munge/munge.key" status=none
    chmod 400 "$D/munge/munge.key"
  fi
  if [ ! -S "$D/munge/munge.socket" ] || ! munge -n -S "$D/munge/munge.socket" >/dev/null 2>&1; then
    munged --force --key-file="$D/munge/munge.key" --socket="$D/munge/munge.socket" \
      --pid-file="$D/munge/munged.pid" --log-file="$D/log/munged.log" --seed-file="$D/munge/munged.seed"
  fi
  write_conf
  slurmctld -f "$CONF" -c
  slurmd -f "$CONF"
  local host; host=$(hostname -s)
  for _ in $(seq 1 60); do
    if status; then echo "slurm-local: up ($CONF, node $host $(node_state))"; return 0; fi
    case "$(node_state)" in
      down*|drain*|fail*) scontrol update nodename="$host" state=resume >/dev/null 2>&1 || true ;;
    esac
    sleep 1
  done
  echo "slurm-local: the node did not become idle in 60 s; state: $(node_state)" >&2
  tail -n 20 "$D"/log/*.log >&2 || true
  return 1
}

stop_pid() {  # stop the daemon whose pid file is $1 (only that pid)
  local f=$1 pid
  [ -f "$f" ] || return 0
  pid=$(cat "$f")
  if [ -n "$pid" ] && kill -0 "$pid" 2>/dev/null; then
    kill "$pid" 2>/dev/null || true
    for _ in $(seq 1 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
    kill -0 "$pid" 2>/dev/null && kill -9 "$pid" 2>/dev/null || true
  fi
  rm -f "$f"
}

down() {
  export PATH=$PATH:/usr/sbin
  if [ -f "$CONF" ]; then timeout 10 scancel --full --quiet --partition=debug 2>/dev/null || true; fi
  stop_pid "$D/slurmd.pid"
  stop_pid "$D/slurmctld.pid"
  stop_pid "$D/munge/munged.pid"
  if [ -z "${WORKBENCH_SLURM_KEEP:-}" ]; then rm -rf "$D"; fi
  echo "slurm-local: down"
}

case "${1:-}" in
  up) up ;;
  down) down ;;
  status) status ;;
  env) echo "SLURM_CONF=$CONF" ;;
  *) echo "usage: $0 up|down|status|env" >&2; exit 2 ;;
esac
