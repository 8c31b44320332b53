# shellcheck shell=bash
# A throwaway one-node SLURM cluster (Debian's slurm-wlm 22.05 + munge): config, key,
# state, spool, logs and pid files under one directory; nothing in /etc is touched. The
# only system paths used are munged's default socket (/run/munge) and the link slurmd's
# configless mode keeps to its config (/run/slurm/conf): one such cluster at a time.
#
# Source this file, then:
#   slurm_install                  # apt-get the packages if sbatch/slurmctld/munged are missing
#   slurm_start DIR                # munged + slurmctld + slurmd, waits for the node to be idle
#   slurm_stop                     # stops exactly the daemons slurm_start started (pid files)
# slurm_start exports SLURM_CONF, so sbatch/squeue/scancel/sinfo in this shell and its
# children (Snakemake and its executor plugin) talk to this cluster.
# Needs root (the daemons run as root, SlurmUser=root, no cgroups: fits a container).

SLURM_DIR=
SLURM_PIDFILES=()

slurm_die() { echo "run_slurm: ERROR: $*" >&2; exit 1; }
slurm_log() { echo "run_slurm: $*" >&2; }

slurm_install() {
    local missing=0 tool
    export PATH="$PATH:/usr/sbin"
    for tool in sbatch squeue scancel sinfo slurmctld slurmd munged mungekey; do
        command -v "$tool" >/dev/null 2>&1 || missing=1
    done
    if [ "$missing" = 0 ]; then
        return 0
    fi
    [ "$(id -u)" = 0 ] || slurm_die "slurm-wlm/munge are not installed and installing them needs root"
    command -v apt-get >/dev/null 2>&1 || slurm_die "slurm-wlm/munge are not installed and apt-get is not available"
    slurm_log "installing slurm-wlm and munge with apt-get (one-off, ~1 min)"
    apt-get update -qq >/dev/null || slurm_die "apt-get update failed"
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq slurm-wlm munge >/dev/null \
        || slurm_die "apt-get install slurm-wlm munge failed"
}

# Two free TCP ports on localhost (controller, node daemon).
_slurm_free_ports() {
    python3 - <<'EOF'
import socket
socks = [socket.socket() for _ in range(2)]
for s in socks:
    s.bind(("127.0.0.1", 0))
print(" ".join(str(s.getsockname()[1]) for s in socks))
for s in socks:
    s.close()
EOF
}

# Wait until "$@" succeeds, at most $1 seconds. Usage: _slurm_wait SECONDS cmd args...
_slurm_wait() {
    local limit=$1 t=0
    shift
    until "$@" >/dev/null 2>&1; do
        t=$((t + 1))
        [ "$t" -le "$((limit * 5))" ] || return 1
        sleep 0.2
    done
}

# alive = exists and is not a zombie (pid 1 in a container may reap late)
_slurm_alive() {
    local state
    state=$(ps -o stat= -p "$1" 2>/dev/null) || return 1
    [ -n "$state" ] && [ "${state#Z}" = "$state" ]
}

_slurm_dead() { ! _slurm_alive "$1"; }

_slurm_munge_ok() {  # a credential made by munged decodes again
    local out
    out=$(munge -n 2>/dev/null | unmunge 2>/dev/null) || return 1
    [[ "$out" =~ STATUS:\ +Success ]]
}

_slurm_node_idle() { [ "$(sinfo -h -n "$SLURM_NODE" -o %T 2>/dev/null)" = idle ]; }

slurm_start() {
    SLURM_DIR=$1
    export PATH="$PATH:/usr/sbin"
    [ "$(id -u)" = 0 ] || slurm_die "the test cluster runs its daemons as root: run as root"
    mkdir -p "$SLURM_DIR"/{munge,state,spool,log,run}
    chmod 700 "$SLURM_DIR/munge"
    SLURM_PIDFILES=()

    # munge on its default socket: slurmd in configless mode (below) authenticates before
    # it has any config, so it can only use the default. Reuse a munged that already
    # answers there; otherwise start one with a fresh key (its pid file is ours to stop).
    if _slurm_munge_ok; then
        slurm_log "using the munged already running on the default socket"
    else
        mkdir -p /run/munge
        chmod 755 /run/munge
        mungekey --create --keyfile="$SLURM_DIR/munge/munge.key" || slurm_die "mungekey failed"
        munged --force --key-file="$SLURM_DIR/munge/munge.key" \
            --pid-file="$SLURM_DIR/run/munged.pid" --log-file="$SLURM_DIR/log/munged.log" \
            --seed-file="$SLURM_DIR/munge/munged.seed" \
            || slurm_die "munged did not start (see $SLURM_DIR/log/munged.log)"
        SLURM_PIDFILES+=("$SLURM_DIR/run/munged.pid")
        _slurm_munge_ok || slurm_die "munge round trip failed (see $SLURM_DIR/log/munged.log)"
    fi

    # slurm.conf: one node = this machine, one default partition, no accounting, no cgroups
    local mem
    read -r SLURM_CTLD_PORT SLURM_NODE_PORT <<<"$(_slurm_free_ports)"
    SLURM_NODE=$(hostname -s)
    SLURM_PARTITION=debug
    mem=$(awk '/MemTotal/ {print int($2 / 1024 * 0.8)}' /proc/meminfo)
    export SLURM_CONF="$SLURM_DIR/slurm.conf"
    cat >"$SLURM_CONF" <<EOF
ClusterName=lubecontact-test
SlurmctldHost=$SLURM_NODE(127.0.0.1)
SlurmctldPort=$SLURM_CTLD_PORT
SlurmdPort=$SLURM_NODE_PORT
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
StateSaveLocation=$SLURM_DIR/state
SlurmdSpoolDir=$SLURM_DIR/spool
SlurmctldPidFile=$SLURM_DIR/run/slurmctld.pid
SlurmdPidFile=$SLURM_DIR/run/slurmd.pid
SlurmctldLogFile=$SLURM_DIR/log/slurmctld.log
SlurmdLogFile=$SLURM_DIR/log/slurmd.log
SlurmctldDebug=info
SlurmdDebug=info
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
MpiDefault=none
SwitchType=switch/none
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
AccountingStorageType=accounting_storage/none
JobAcctGatherType=jobacct_gather/none
JobCompType=jobcomp/none
ReturnToService=2
# configless: slurmd fetches this file from slurmctld and caches it where client commands
# on the node look (/run/slurm/conf): srun inside a job has no SLURM_CONF (the Snakemake
# jobstep plugin strips SLURM_* variables before calling srun)
SlurmctldParameters=enable_configless
# keep finished jobs visible to squeue long enough for Snakemake's squeue status check
MinJobAge=600
KillWait=5
InactiveLimit=0
NodeName=$SLURM_NODE NodeAddr=127.0.0.1 CPUs=$(nproc) RealMemory=$mem State=UNKNOWN
PartitionName=$SLURM_PARTITION Nodes=$SLURM_NODE Default=YES MaxTime=INFINITE State=UP
EOF
    slurmctld -f "$SLURM_CONF" || slurm_die "slurmctld did not start (see $SLURM_DIR/log/slurmctld.log)"
    SLURM_PIDFILES+=("$SLURM_DIR/run/slurmctld.pid")
    slurmd --conf-server "127.0.0.1:$SLURM_CTLD_PORT" -N "$SLURM_NODE" || slurm_die "slurmd did not start (see $SLURM_DIR/log/slurmd.log)"
    SLURM_PIDFILES+=("$SLURM_DIR/run/slurmd.pid")
    _slurm_wait 60 _slurm_node_idle \
        || slurm_die "node $SLURM_NODE not idle after 60 s: $(sinfo 2>&1); see $SLURM_DIR/log/"
    export SLURM_NODE SLURM_PARTITION
    slurm_log "cluster up: node $SLURM_NODE ($(nproc) CPUs, $mem MB), partition $SLURM_PARTITION, conf $SLURM_CONF"
}

_slurm_descendants() {
    local child
    for child in $(ps -o pid= --ppid "$1"); do
        echo "$child"
        _slurm_descendants "$child"
    done
}

# SIGKILL, all at once, every process of the given jobs (the descendants of their
# slurmstepd), as if their node had died: nothing in them gets to clean up. (scancel
# --signal=KILL cannot do this here: proctrack/linuxproc loses a killed shell's children.)
slurm_crash_jobs() {
    local id pid args pids=()
    for id in "$@"; do
        while read -r pid args; do
            case "$args" in
                "slurmstepd: [$id."*) mapfile -t -O "${#pids[@]}" pids < <(_slurm_descendants "$pid") ;;
            esac
        done < <(ps -eo pid=,args=)
    done
    [ ${#pids[@]} -eq 0 ] || kill -KILL "${pids[@]}" 2>/dev/null || true
}

# Stop the daemons started by slurm_start, newest first, by pid file; SIGKILL after 10 s.
# Removes slurmd's /run/slurm/conf link if it still points into this cluster's directory.
slurm_stop() {
    local i pidfile pid
    for ((i = ${#SLURM_PIDFILES[@]} - 1; i >= 0; i--)); do
        pidfile=${SLURM_PIDFILES[i]}
        [ -s "$pidfile" ] || continue
        pid=$(cat "$pidfile")
        _slurm_alive "$pid" || continue
        kill "$pid" 2>/dev/null || continue
        _slurm_wait 10 _slurm_dead "$pid" || kill -9 "$pid" 2>/dev/null
    done
    SLURM_PIDFILES=()
    if [ -n "$SLURM_DIR" ]; then
        case "$(readlink /run/slurm/conf 2>/dev/null)" in
            "$SLURM_DIR"/*) rm -f /run/slurm/conf ;;
        esac
    fi
}
