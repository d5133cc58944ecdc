# A single-node Slurm for tests and benchmarks (sourced): start_slurm writes $slurm_dir/slurm.conf for this host
# (CPUs=2, AuthType=auth/none: no munge; random ports; state, spool, logs and PID files under $slurm_dir), starts
# slurmctld and slurmd as daemons, exports SLURM_CONF, waits until the node is idle and stops both by PID on exit.
# A daemon that does not come up fails (exit 1) with its log. Needs root (slurmd launches the tasks) and slurm-wlm.
stop_slurm() {
  local jobs
  jobs=$(squeue -h -o %i 2>/dev/null || true)
  [ -z "$jobs" ] || scancel $jobs 2>/dev/null || true
  for d in slurmd slurmctld; do
    [ -f "$slurm_dir/$d.pid" ] || continue
    pid=$(cat "$slurm_dir/$d.pid")
    kill "$pid" 2>/dev/null || continue
    for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
    kill -9 "$pid" 2>/dev/null || true
  done
}
daemon_failed() {
  echo "FAIL: $1 did not start; its log:" >&2
  cat "$slurm_dir/log/$1.log" >&2 2>/dev/null || echo "(no log written)" >&2
  cat "$slurm_dir/log/$1.out" >&2 2>/dev/null || true
  exit 1
}
start_slurm() {
  mkdir -p "$slurm_dir"/{state,spool,log}
  local host port
  host=$(hostname -s)
  port=$((20000 + RANDOM % 20000))
  cat > "$slurm_dir/slurm.conf" <<CONF
ClusterName=trisplinefarm
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$port
SlurmdPort=$((port + 1))
AuthType=auth/none
CredType=cred/none
SlurmUser=$(id -un)
StateSaveLocation=$slurm_dir/state
SlurmdSpoolDir=$slurm_dir/spool
SlurmctldPidFile=$slurm_dir/slurmctld.pid
SlurmdPidFile=$slurm_dir/slurmd.pid
SlurmctldLogFile=$slurm_dir/log/slurmctld.log
SlurmdLogFile=$slurm_dir/log/slurmd.log
SlurmdParameters=config_overrides
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
ReturnToService=2
SchedulerParameters=sched_interval=1,bf_interval=1
MinJobAge=600
NodeName=$host NodeAddr=127.0.0.1 CPUs=2 State=UNKNOWN
PartitionName=farm Nodes=ALL Default=YES MaxTime=INFINITE State=UP
CONF
  export SLURM_CONF=$slurm_dir/slurm.conf
  trap stop_slurm EXIT
  command -v slurmctld >/dev/null || PATH=$PATH:/usr/sbin
  slurmctld -f "$SLURM_CONF" >"$slurm_dir/log/slurmctld.out" 2>&1 || daemon_failed slurmctld
  slurmd -f "$SLURM_CONF" >"$slurm_dir/log/slurmd.out" 2>&1 || daemon_failed slurmd
  for _ in $(seq 100); do
    [ "$(sinfo -h -o %T 2>/dev/null)" = idle ] && return 0
    sleep 0.2
  done
  for d in slurmctld slurmd; do
    { [ -f "$slurm_dir/$d.pid" ] && kill -0 "$(cat "$slurm_dir/$d.pid")" 2>/dev/null; } || daemon_failed $d
  done
  sinfo >&2 || true
  daemon_failed slurmd
}

