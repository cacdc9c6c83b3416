#!/usr/bin/env bash
# A real single-node Slurm cluster on this machine, as root, from Debian's slurm-wlm and munge,
# for running the solve step through LAUNCH="srun ..." (tests/README.md, "A Slurm cluster").
#
# usage: tests/slurm/cluster.sh start | stop | status | env
#   start   install slurmctld, slurmd, slurm-client and munge if missing (tools/install-deps.sh --slurm),
#           make a munge key, start munged, slurmctld and slurmd, wait until sinfo shows the node
#           idle; quiet on success, and a no-op when the cluster is already up
#   stop    stop the three daemons (and any job still running); a no-op when none runs
#   status  one line per daemon and the node's state; exit 0 when all are up and the node is usable
#   env     prints `export SLURM_CONF=...`: srun, sinfo, ... need it to find this cluster
#
# Everything lives in a private state folder, HELIOS_SLURM_DIR (default /var/tmp/helios-slurm):
# slurm.conf, the munge key and socket, pid files, logs, slurmctld's state and the job completion
# log (jobcomp.log, one line per finished job: the cluster keeps no accounting database). Nothing is
# written to /etc, so Debian's own slurm services stay inert (they start only with
# /etc/slurm/slurm.conf) and a system munged, if one runs, is left alone. No systemd is needed:
# the daemons are started directly and found again through their pid files.
# Other knobs: HELIOS_SLURM_PORT (slurmctld's port, default 6817; slurmd uses the next one),
# HELIOS_SLURM_TIMEOUT (seconds to wait for an idle node, default 60).
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
STATE="${HELIOS_SLURM_DIR:-/var/tmp/helios-slurm}"
PORT="${HELIOS_SLURM_PORT:-6817}"
TIMEOUT="${HELIOS_SLURM_TIMEOUT:-60}"
CONF="$STATE/slurm.conf"
SOCKET="$STATE/munge/munge.socket.2"
HOST="$(hostname -s)"
export SLURM_CONF="$CONF"
PATH="$PATH:/usr/sbin:/sbin"

die() {
  echo "cluster.sh: error: $*" >&2
  exit 1
}

# pid_of NAME: the pid in NAME's pid file when that process is alive and is NAME, else nothing.
pid_of() {
  local name="$1" pid
  [[ -r "$STATE/$name.pid" ]] || return 0
  pid="$(tr -dc 0-9 <"$STATE/$name.pid")"
  [[ -n $pid && -r /proc/$pid/comm ]] || return 0
  # slurmd runs as slurmd-wlm through Debian's alternatives link; /proc/PID/comm is 15 bytes at most.
  [[ $(cat "/proc/$pid/comm" 2>/dev/null) == "$name"* ]] && echo "$pid"
  return 0
}

# node_state: the node's state as sinfo prints it (idle, mix, alloc, down*, drain, ...), or nothing.
node_state() {
  timeout 10 sinfo -h -n "$HOST" -o %t 2>/dev/null | head -1 || true
}

usable() {
  [[ $1 == idle || $1 == mix || $1 == alloc || $1 == comp ]]
}

write_conf() {
  local cpus mem_mb tmp
  cpus="$(nproc)"
  mem_mb="$(awk '/^MemTotal:/ { print int($2 / 1024) }' /proc/meminfo)"
  [[ $mem_mb -gt 0 ]] || die "cannot read MemTotal from /proc/meminfo"
  tmp="$CONF.new"
  cat >"$tmp" <<EOF
# Written by tests/slurm/cluster.sh: a single-node cluster on $HOST (rewritten at each start).
ClusterName=helios
SlurmctldHost=$HOST(127.0.0.1)
SlurmctldPort=$PORT
SlurmdPort=$((PORT + 1))
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$SOCKET
StateSaveLocation=$STATE/slurmctld
SlurmdSpoolDir=$STATE/slurmd
SlurmctldPidFile=$STATE/slurmctld.pid
SlurmdPidFile=$STATE/slurmd.pid
SlurmctldLogFile=$STATE/slurmctld.log
SlurmdLogFile=$STATE/slurmd.log
MpiDefault=none
MailProg=/bin/true
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SchedulerType=sched/builtin
AccountingStorageType=accounting_storage/none
JobAcctGatherType=jobacct_gather/none
JobCompType=jobcomp/filetxt
JobCompLoc=$STATE/jobcomp.log
ReturnToService=2
InactiveLimit=0
KillWait=5
MinJobAge=300
NodeName=$HOST NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=$mem_mb State=UNKNOWN
PartitionName=debug Nodes=$HOST Default=YES MaxTime=INFINITE State=UP
EOF
  if cmp -s "$tmp" "$CONF"; then rm -f "$tmp"; else mv "$tmp" "$CONF"; fi
}

# fail_start MESSAGE: stop what was started, print MESSAGE with the logs' last lines, exit 1.
fail_start() {
  local msg="$1" log
  {
    echo "cluster.sh: error: $msg"
    for log in munged slurmctld slurmd; do
      [[ -s "$STATE/$log.log" ]] || continue
      echo "--- last lines of $STATE/$log.log:"
      tail -n 8 "$STATE/$log.log"
    done
  } >&2
  do_stop
  exit 1
}

# wait_pid NAME: a daemon that forked into the background has written its pid file (10 s at most).
wait_pid() {
  local i
  for ((i = 0; i < 100; i++)); do
    [[ -n $(pid_of "$1") ]] && return 0
    sleep 0.1
  done
  fail_start "$1 wrote no live pid to $STATE/$1.pid within 10 s"
}

do_start() {
  [[ $(id -u) -eq 0 ]] || die "start needs root (it runs slurmctld, slurmd and munged as root)"
  "$ROOT/tools/install-deps.sh" --slurm
  mkdir -p "$STATE"
  chmod 0755 "$STATE"
  # Starts and stops are serialized; each daemon is started with this descriptor (9) closed, or
  # it would hold the lock for as long as it runs.
  exec 9>"$STATE/.lock"
  flock -w 120 9 || die "another cluster.sh holds $STATE/.lock"

  if [[ -n $(pid_of munged) && -n $(pid_of slurmctld) && -n $(pid_of slurmd) ]] && usable "$(node_state)"; then
    return 0
  fi
  mkdir -p "$STATE/munge" "$STATE/slurmctld" "$STATE/slurmd"
  chmod 0755 "$STATE/munge"
  chmod 0700 "$STATE/slurmctld" "$STATE/slurmd"
  if [[ ! -s "$STATE/munge.key" ]]; then
    mungekey --create --keyfile="$STATE/munge.key" 2>/dev/null ||
      dd if=/dev/urandom of="$STATE/munge.key" bs=1024 count=1 status=none
  fi
  chmod 0600 "$STATE/munge.key"

  if [[ -z $(pid_of munged) ]]; then
    rm -f "$SOCKET" "$SOCKET.lock"
    munged --socket="$SOCKET" --key-file="$STATE/munge.key" --pid-file="$STATE/munged.pid" \
      --log-file="$STATE/munged.log" --seed-file="$STATE/munged.seed" 9>&- ||
      fail_start "munged did not start"
  fi
  munge -n -S "$SOCKET" 2>/dev/null | unmunge -S "$SOCKET" >/dev/null 2>&1 ||
    fail_start "munged runs but a credential does not round-trip through $SOCKET"

  write_conf
  if [[ -z $(pid_of slurmctld) ]]; then
    slurmctld -c -f "$CONF" 9>&- || fail_start "slurmctld did not start"
    wait_pid slurmctld
  fi
  if [[ -z $(pid_of slurmd) ]]; then
    slurmd -c -f "$CONF" 9>&- || fail_start "slurmd did not start"
    wait_pid slurmd
  fi

  local deadline=$((SECONDS + TIMEOUT)) state="" resumed=0
  while ((SECONDS < deadline)); do
    state="$(node_state)"
    usable "$state" && return 0
    # A node left drained (or down) by an earlier run is resumed once; ReturnToService=2 covers
    # only a node that was down for not responding.
    if [[ $state == drain* || $state == down* ]] && ((!resumed)); then
      timeout 10 scontrol update NodeName="$HOST" State=RESUME >/dev/null 2>&1 || true
      resumed=1
    fi
    [[ -n $(pid_of slurmctld) ]] || fail_start "slurmctld exited"
    [[ -n $(pid_of slurmd) ]] || fail_start "slurmd exited"
    sleep 1
  done
  fail_start "node $HOST not idle after ${TIMEOUT}s (sinfo state: ${state:-none}; sinfo: $(timeout 10 sinfo 2>&1 | tr '\n' ' '))"
}

# stop_daemon NAME: TERM, up to 15 s, then KILL.
stop_daemon() {
  local name="$1" pid i
  pid="$(pid_of "$name")"
  if [[ -n $pid ]]; then
    kill -TERM "$pid" 2>/dev/null || true
    for ((i = 0; i < 150; i++)); do
      [[ -d /proc/$pid ]] || break
      sleep 0.1
    done
    if [[ -d /proc/$pid ]]; then
      echo "cluster.sh: $name ($pid) ignored SIGTERM for 15 s; killing it" >&2
      kill -KILL "$pid" 2>/dev/null || true
    fi
  fi
  rm -f "$STATE/$name.pid"
}

do_stop() {
  [[ -d $STATE ]] || return 0
  local jobs
  if [[ -n $(pid_of slurmctld) ]]; then
    # A job still running would leave its slurmstepd behind slurmd.
    jobs="$(timeout 10 squeue -h -o %A 2>/dev/null || true)"
    if [[ -n $jobs ]]; then
      # shellcheck disable=SC2086 # one argument per job id
      timeout 10 scancel --quiet $jobs >/dev/null 2>&1 || true
      sleep 2
    fi
  fi
  stop_daemon slurmd
  stop_daemon slurmctld
  stop_daemon munged
  rm -f "$SOCKET" "$SOCKET.lock"
}

do_status() {
  local name pid ok=0 state
  for name in munged slurmctld slurmd; do
    pid="$(pid_of "$name")"
    if [[ -n $pid ]]; then echo "$name: running (pid $pid)"; else echo "$name: not running"; ok=1; fi
  done
  state="$(node_state)"
  echo "node $HOST: ${state:-unknown} (SLURM_CONF=$CONF)"
  usable "$state" || ok=1
  return "$ok"
}

case "${1:-}" in
  start) do_start ;;
  stop)
    if [[ -d $STATE ]]; then
      exec 9>"$STATE/.lock"
      flock -w 120 9 || die "another cluster.sh holds $STATE/.lock"
    fi
    do_stop
    ;;
  status) do_status ;;
  env) echo "export SLURM_CONF=$CONF" ;;
  *)
    echo "usage: tests/slurm/cluster.sh start|stop|status|env" >&2
    exit 2
    ;;
esac
