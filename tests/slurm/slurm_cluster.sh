#!/usr/bin/env bash
# Starts a private single-node Slurm cluster (munged, slurmctld, slurmd) in a temporary
# folder, for slurm_array_test.sh to source. Everything it starts is stopped by
# stop_slurm_cluster (the caller's EXIT trap). Sets SLURM_CONF for the client commands.
#
# Exits 77 (ctest's skip) only where the daemons cannot run here for reasons outside the
# project (not root and not the munge/slurm users, no free port); a configuration that
# Slurm refuses is a failure.

slurm_pids=()

stop_slurm_cluster() {
  local pid
  for pid in "${slurm_pids[@]}"; do
    kill "$pid" 2>/dev/null || true
  done
  for pid in "${slurm_pids[@]}"; do
    wait "$pid" 2>/dev/null || true
  done
  slurm_pids=()
}

skip() {
  echo "SKIP: $*"
  exit 77
}

free_port() {
  python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])'
}

# start_slurm_cluster DIR CPUS
start_slurm_cluster() {
  local dir=$1 cpus=$2
  for tool in munged slurmctld slurmd sbatch squeue scancel sinfo; do
    command -v "$tool" >/dev/null || {
      echo "FAIL: $tool is missing: tools/setup.sh installs slurm-wlm and munge"
      exit 1
    }
  done
  # The daemons run as this user (SlurmUser, SlurmdUser); slurmd runs jobs as their owner,
  # which only root can do for others, but a job of our own needs no switch.
  mkdir -p "$dir"/{munge,state,spool,log}
  chmod 711 "$dir/munge"  # munged wants its socket's folder searchable by all
  head -c 1024 /dev/urandom >"$dir/munge/munge.key"
  chmod 400 "$dir/munge/munge.key"
  local socket=$dir/munge/munge.socket
  munged --key-file="$dir/munge/munge.key" --socket="$socket" \
    --pid-file="$dir/munge/munged.pid" --log-file="$dir/log/munged.log" \
    --seed-file="$dir/munge/munge.seed" --foreground --force >>"$dir/log/munged.out" 2>&1 &
  slurm_pids+=($!)
  for _ in $(seq 50); do
    [ -S "$socket" ] && break
    sleep 0.1
  done
  [ -S "$socket" ] || {
    cat "$dir/log/munged.out" 2>/dev/null
    skip "munged did not start here (its log is above)"
  }
  local user ctld_port slurmd_port memory
  user=$(id -un)
  ctld_port=$(free_port) slurmd_port=$(free_port)
  memory=$(awk '/MemTotal/ { print int($2 / 1024 / 2) }' /proc/meminfo)
  cat >"$dir/slurm.conf" <<CONF
ClusterName=memograph-test
SlurmctldHost=localhost
SlurmUser=$user
SlurmdUser=$user
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$socket
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
MpiDefault=none
ReturnToService=2
SlurmctldTimeout=30
SlurmdTimeout=30
MinJobAge=300
NodeName=localhost NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=$memory State=UNKNOWN
PartitionName=test Nodes=localhost Default=YES MaxTime=INFINITE State=UP
CONF
  export SLURM_CONF=$dir/slurm.conf
  # In the foreground (-D), so that each is a child whose pid the trap stops.
  slurmctld -D -i -f "$SLURM_CONF" >>"$dir/log/slurmctld.out" 2>&1 &
  slurm_pids+=($!)
  slurmd -D -N localhost -f "$SLURM_CONF" >>"$dir/log/slurmd.out" 2>&1 &
  slurm_pids+=($!)
  local state=""
  for _ in $(seq 100); do
    state=$(sinfo -h -N -o %t 2>/dev/null || true)
    case "$state" in idle*) return 0 ;; esac
    sleep 0.2
  done
  echo "--- slurmctld.log"
  tail -20 "$dir/log/slurmctld.log" 2>/dev/null
  echo "--- slurmd.log"
  tail -20 "$dir/log/slurmd.log" 2>/dev/null
  echo "FAIL: the node did not come up idle within 20 s (sinfo: '${state}')"
  exit 1
}
