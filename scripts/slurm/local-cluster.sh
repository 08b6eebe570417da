#!/usr/bin/env bash
# Starts or stops a one-node Slurm cluster on 127.0.0.1 whose every file lives under DIR:
# slurm.conf, the munge key and socket, the controller's state, slurmd's spool, the logs and
# the pid files. It needs no systemd and does not touch a system munged or Slurm: munged gets
# its own key, socket and pid file under DIR, and slurm.conf points Slurm at that socket.
# For tests (tests/cluster/slurm_dataset_test.sh) and for trying scripts/slurm/ by hand.
#
# Usage: scripts/slurm/local-cluster.sh start DIR
#        scripts/slurm/local-cluster.sh stop DIR
#   start  prints `export SLURM_CONF=DIR/slurm.conf` on stdout once `sinfo` says the node is
#          idle, so `eval "$(scripts/slurm/local-cluster.sh start DIR)"` readies the shell.
#          Everything else goes to stderr. Fails if DIR's cluster already runs, if a port is
#          taken, or if the node is not idle within LOCAL_SLURM_TIMEOUT seconds.
#   stop   cancels the cluster's jobs, then stops exactly the daemons that `start` wrote into
#          DIR/*.pid (TERM, then KILL after 10 s). Stopping a cluster that is not running is
#          not an error.
# Environment:
#   LOCAL_SLURM_CTLD_PORT  slurmctld's port (default 6817)
#   LOCAL_SLURM_D_PORT     slurmd's port (default 6818)
#   LOCAL_SLURM_CPUS       CPUs of the node (default: nproc)
#   LOCAL_SLURM_TIMEOUT    seconds to wait for the node to be idle (default 30)
# Needs root (the daemons run as root; SlurmUser=root) and the packages slurm-wlm,
# slurm-client and munge (scripts/install-deps.sh).
set -euo pipefail

die() { echo "error: local-cluster.sh: $*" >&2; exit 1; }
note() { echo "local-cluster.sh: $*" >&2; }

[ $# -eq 2 ] || die "usage: local-cluster.sh start|stop DIR"
action=$1
case "$action" in start | stop) ;; *) die "unknown action '$action' (expected start or stop)" ;; esac
[ -n "$2" ] || die "DIR is empty"
if [ "$action" = stop ] && [ ! -d "$2" ]; then note "no cluster was running in $2"; exit 0; fi
mkdir -p "$2" || die "cannot create '$2'"
DIR=$(cd "$2" && pwd -P)
# slurm.conf has no quoting, and AuthInfo is a comma-separated list.
[[ "$DIR" =~ ^[A-Za-z0-9._/+@-]+$ ]] ||
  die "DIR '$DIR' has a character slurm.conf cannot hold (only letters, digits and ._/+@- work)"

DAEMONS=(munged slurmctld slurmd)   # started in this order, stopped in the reverse one

# The pid in DIR/NAME.pid if that process is alive (not a zombie) and is the one `start`
# launched: its command line names the binary and DIR. Prints nothing otherwise.
live_pid() {
  local name=$1 pidfile="$DIR/$1.pid" pid cmd state
  [ -f "$pidfile" ] || return 0
  pid=$(tr -dc '0-9' <"$pidfile")
  [ -n "$pid" ] && [ -r "/proc/$pid/cmdline" ] || return 0
  state=$(sed -n 's/^State:[[:space:]]*\([A-Z]\).*/\1/p' "/proc/$pid/status" 2>/dev/null || true)
  [ "$state" != Z ] || return 0
  cmd=$(tr '\0' ' ' <"/proc/$pid/cmdline" 2>/dev/null || true)
  case "$cmd" in
    *"$name"*"$DIR/"*) echo "$pid" ;;
  esac
}

# Whether a cgroup filesystem (v1 or v2) is mounted at /sys/fs/cgroup or below.
has_cgroup_fs() {
  awk '$2 ~ "^/sys/fs/cgroup" && $3 ~ "^cgroup" { found = 1 } END { exit !found }' /proc/mounts
}

port_in_use() {
  local port=$1
  if command -v ss >/dev/null; then
    [ -n "$(ss -Htln "sport = :$port" 2>/dev/null)" ]
  else
    (exec 3<>"/dev/tcp/127.0.0.1/$port") 2>/dev/null
  fi
}

stop_cluster() {
  local name pid i any=0
  # Cancel the cluster's jobs first so that no job step outlives slurmd.
  if [ -n "$(live_pid slurmctld)" ] && [ -f "$DIR/slurm.conf" ]; then
    if SLURM_CONF="$DIR/slurm.conf" timeout 5 scancel --user="$(id -un)" 2>/dev/null; then
      for i in $(seq 20); do
        [ -z "$(SLURM_CONF="$DIR/slurm.conf" timeout 5 squeue -h -o %i 2>/dev/null)" ] && break
        sleep 0.25
      done
    fi
  fi
  for ((i = ${#DAEMONS[@]} - 1; i >= 0; i--)); do
    name=${DAEMONS[i]}
    pid=$(live_pid "$name")
    if [ -n "$pid" ]; then
      any=1
      kill -TERM "$pid" 2>/dev/null || true
      local _
      for _ in $(seq 100); do
        [ -n "$(live_pid "$name")" ] || break
        sleep 0.1
      done
      if [ -n "$(live_pid "$name")" ]; then
        note "$name (pid $pid) ignored SIGTERM for 10 s; sending SIGKILL"
        kill -KILL "$pid" 2>/dev/null || true
        sleep 0.2
      fi
    elif [ -f "$DIR/$name.pid" ]; then
      note "$name: stale pid file $DIR/$name.pid (process gone or not ours); removing it"
    fi
    rm -f "$DIR/$name.pid"
  done
  if [ $any -eq 1 ]; then note "stopped the cluster in $DIR"; else note "no cluster was running in $DIR"; fi
}

start_cluster() {
  local name
  for name in "${DAEMONS[@]}"; do
    [ -z "$(live_pid "$name")" ] ||
      die "a cluster already runs in $DIR ($name pid $(live_pid "$name")); run 'local-cluster.sh stop $DIR' first"
  done
  for name in "${DAEMONS[@]}"; do rm -f "$DIR/$name.pid"; done

  for cmd in munged mungekey munge slurmctld slurmd sinfo scontrol; do
    command -v "$cmd" >/dev/null ||
      die "'$cmd' not found; install slurm-wlm, slurm-client and munge (scripts/install-deps.sh)"
  done
  [ "$(id -u)" -eq 0 ] || die "must run as root (the daemons run as root with SlurmUser=root)"

  local ctld_port=${LOCAL_SLURM_CTLD_PORT:-6817} d_port=${LOCAL_SLURM_D_PORT:-6818}
  local cpus=${LOCAL_SLURM_CPUS:-$(nproc)} timeout=${LOCAL_SLURM_TIMEOUT:-30}
  local p
  for p in "$ctld_port" "$d_port"; do
    [[ "$p" =~ ^[0-9]+$ ]] || die "port '$p' is not a number"
    port_in_use "$p" &&
      die "port $p is already in use (another Slurm?); set LOCAL_SLURM_CTLD_PORT / LOCAL_SLURM_D_PORT"
  done
  [ "$ctld_port" != "$d_port" ] || die "slurmctld and slurmd ports are both $ctld_port"
  # slurmd 22.05 starts its cgroup plugin whatever slurm.conf says (ProctrackType and
  # TaskPlugin need none here) and gives up without a cgroup filesystem: a chroot whose /sys
  # is bound without its submounts, or a container without one.
  has_cgroup_fs ||
    die "no cgroup filesystem is mounted on /sys/fs/cgroup (a chroot or a bare container?): slurmd cannot start without one"

  # munged insists that the socket's folder and every folder above it be searchable by all,
  # and that the key be readable by its owner only.
  local sock="$DIR/run/munge.socket"
  [ ${#sock} -lt 100 ] || die "munge socket path '$sock' is too long for a Unix socket; use a shorter DIR"
  mkdir -p "$DIR/munge" "$DIR/run" "$DIR/state" "$DIR/spool/localhost" "$DIR/log"
  chmod 700 "$DIR/munge"
  chmod 755 "$DIR" "$DIR/run"
  [ -s "$DIR/munge/munge.key" ] || mungekey --create --keyfile="$DIR/munge/munge.key" 2>/dev/null ||
    die "mungekey could not create $DIR/munge/munge.key"
  rm -f "$sock" "$sock.lock"

  cat >"$DIR/slurm.conf" <<EOF
# Written by scripts/slurm/local-cluster.sh: a one-node cluster on loopback.
ClusterName=localtest
SlurmctldHost=localhost(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$d_port
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$sock
MpiDefault=none
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SchedulerType=sched/backfill
# Schedule at once rather than batching submissions (default: 3 s) and test pending jobs,
# dependencies included, every second rather than every minute.
SchedulerParameters=batch_sched_delay=0,sched_interval=1
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
MinJobAge=600
MailProg=/bin/true
StateSaveLocation=$DIR/state
SlurmdSpoolDir=$DIR/spool/%n
SlurmctldPidFile=$DIR/run/slurmctld.pid
SlurmdPidFile=$DIR/run/slurmd.pid
SlurmctldLogFile=$DIR/log/slurmctld.log
SlurmdLogFile=$DIR/log/slurmd.log
NodeName=localhost NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=1000 State=UNKNOWN
PartitionName=debug Nodes=localhost Default=YES MaxTime=INFINITE State=UP
EOF
  export SLURM_CONF="$DIR/slurm.conf"

  # Each daemon runs in the foreground in its own session (so that a Ctrl-C meant for the
  # caller does not hit it; `stop` ends it), with its output in DIR/log/NAME.out. setsid
  # execs in place here (a background job of a script is no process-group leader), so $! is
  # the daemon's own pid.
  local t0; t0=$(date +%s.%N)
  setsid munged --foreground --socket="$sock" --pid-file="$DIR/run/munged.pid" \
    --key-file="$DIR/munge/munge.key" --log-file="$DIR/log/munged.log" \
    --seed-file="$DIR/munge/munged.seed" </dev/null >"$DIR/log/munged.out" 2>&1 &
  echo $! >"$DIR/munged.pid"
  local i
  for i in $(seq 50); do [ -S "$sock" ] && break; sleep 0.1; done
  if ! munge -s local-cluster --socket="$sock" </dev/null 2>/dev/null | unmunge --socket="$sock" >/dev/null 2>&1; then
    stop_cluster 2>/dev/null || true
    die "munged did not start ($(grep -m1 'Error:' "$DIR/log/munged.out" 2>/dev/null | sed 's/^munged: //' || true)); see $DIR/log/munged.out"
  fi

  setsid slurmctld -D -i -f "$DIR/slurm.conf" </dev/null >"$DIR/log/slurmctld.out" 2>&1 &
  echo $! >"$DIR/slurmctld.pid"
  setsid slurmd -D -N localhost -f "$DIR/slurm.conf" </dev/null >"$DIR/log/slurmd.out" 2>&1 &
  echo $! >"$DIR/slurmd.pid"

  local state="" deadline=$((SECONDS + timeout))
  while [ $SECONDS -lt $deadline ]; do
    for name in slurmctld slurmd; do
      if [ -z "$(live_pid "$name")" ]; then
        stop_cluster 2>/dev/null || true
        die "$name exited during start; see $DIR/log/$name.out and $DIR/log/$name.log"
      fi
    done
    state=$(timeout 5 sinfo -h -o '%T' 2>/dev/null | head -n1 || true)
    [ "$state" = idle ] && break
    sleep 0.2
  done
  if [ "$state" != idle ]; then
    stop_cluster 2>/dev/null || true
    die "node not idle after ${timeout} s (sinfo says '${state:-nothing}'); see $DIR/log/slurmctld.log and $DIR/log/slurmd.log"
  fi
  note "cluster up in $DIR after $(awk -v a="$t0" -v b="$(date +%s.%N)" 'BEGIN{printf "%.1f", b-a}') s (ports $ctld_port/$d_port, $cpus CPUs)"
  echo "export SLURM_CONF=$(printf %q "$DIR/slurm.conf")"
}

case "$action" in
  start) start_cluster ;;
  stop) stop_cluster ;;
esac
