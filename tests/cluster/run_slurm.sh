#!/usr/bin/env bash
# Live check of the SLURM path: brings up a throwaway one-node SLURM cluster on this
# machine, runs the tiny study (config/test.yaml) through workflow/profiles/slurm and
# compares it with a local run of the same workflow; then injects two faults into the
# solve jobs (A: scancel one mid-run; B: SIGKILL Snakemake and every job process, a node
# crash) and checks that only complete case files are left and that a rerun solves only
# what is missing. Prints wall times and sbatch counts; exits non-zero with a message.
#
#   sudo tests/cluster/run_slurm.sh          (root: installs slurm-wlm + munge if missing)
#
# Environment:
#   LUBECONTACT_CLUSTER_CONFIG=config/test.yaml   study to run (path inside the workflow)
#   LUBECONTACT_CLUSTER_WORKFLOW=<repo>           where the Snakefile/config/src come from
#   LUBECONTACT_CLUSTER_FAULT=1                   0 skips the two fault checks
#   LUBECONTACT_CLUSTER_KEEP=0                    1 keeps the work directory (kept anyway on failure)
# The local and the cluster run each happen in a copy of the workflow under a temp
# directory (the faults reuse the cluster copy); the repository's results/ is never
# touched. On every exit path the jobs are cancelled and the daemons stopped by pid.
set -euo pipefail

HERE=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
REPO=$(cd "$HERE/../.." && pwd)
SOURCE=${LUBECONTACT_CLUSTER_WORKFLOW:-$REPO}
CONFIG=${LUBECONTACT_CLUSTER_CONFIG:-config/test.yaml}
PY=$REPO/.venv/bin/python
SMK=$REPO/.venv/bin/snakemake
PROFILE=$REPO/workflow/profiles/slurm
# the job group the profile bundles (group-components: NAME: N); the workflow's solve rules
# carry it (group: NAME) and are named after it (NAME_<figure>_<hash>)
GROUP=$("$PY" -c 'import sys, yaml; print(*yaml.safe_load(open(sys.argv[1]))["group-components"])' "$PROFILE/config.yaml")
# shellcheck source=tests/cluster/slurm_lib.sh
source "$HERE/slurm_lib.sh"

[ -x "$SMK" ] || slurm_die "$SMK missing: run scripts/setup.sh first"
[ -n "$GROUP" ] || slurm_die "no 'group-components: NAME: N' entry in $PROFILE/config.yaml"
[ -f "$SOURCE/$CONFIG" ] || slurm_die "$SOURCE/$CONFIG does not exist"
# the study's results directory inside a workflow copy (config key `results`, the study's
# config over config/config.yaml; config/test.yaml: results/test)
RESULTS=$("$PY" -c 'import sys, yaml; c = {}; [c.update(yaml.safe_load(open(f)) or {}) for f in sys.argv[1:]]; print(c.get("results", "results"))' \
    "$SOURCE/config/config.yaml" "$SOURCE/$CONFIG")

WORK=$(mktemp -d "${TMPDIR:-/tmp}/lubecontact-slurm.XXXXXX")
SMK_PID=

finish() {
    local rc=$? queued
    trap - EXIT INT TERM
    if [ -n "$SMK_PID" ]; then
        kill "$SMK_PID" 2>/dev/null || true  # stops submitting, waits for its running jobs
    fi
    if [ ${#SLURM_PIDFILES[@]} -gt 0 ]; then
        queued=$(squeue -h -o %i 2>/dev/null || true)
        if [ -n "$queued" ]; then
            # shellcheck disable=SC2086
            scancel $queued 2>/dev/null || true
            # shellcheck disable=SC2016  # expanded by sh -c, each try
            _slurm_wait 20 sh -c '[ -z "$(squeue -h -o %i)" ]' || true
        fi
    fi
    if [ -n "$SMK_PID" ]; then
        wait "$SMK_PID" 2>/dev/null || true
    fi
    slurm_stop
    if [ "$rc" = 0 ] && [ "${LUBECONTACT_CLUSTER_KEEP:-0}" != 1 ]; then
        rm -rf "$WORK"
    else
        echo "run_slurm: work directory kept: $WORK (run logs: $WORK/*.log; daemons: $WORK/slurm/log)" >&2
    fi
    exit "$rc"
}
trap finish EXIT
trap 'exit 130' INT TERM

# Snakemake runs in the background and is waited for, so that a TERM to this script is
# handled at once (bash defers traps while a foreground child runs).
smk_start() {  # DIR LOG ARGS...: start snakemake in DIR, output to LOG; sets SMK_PID
    local dir=$1 log=$2
    shift 2
    (cd "$dir" && exec "$SMK" "$@") >"$log" 2>&1 &
    SMK_PID=$!
}
smk_wait() {  # exit status of the snakemake started last
    local rc=0
    wait "$SMK_PID" || rc=$?
    SMK_PID=
    return "$rc"
}
smk() { smk_start "$@" && smk_wait; }  # DIR LOG ARGS...

fail_with_log() {  # message, log file
    echo "----- last lines of $2 -----" >&2
    tail -n 40 "$2" >&2 || true
    slurm_die "$1 (full log: $2)"
}

copy_workflow() {  # a fresh copy of the workflow without results, caches or the venv
    mkdir -p "$1"
    tar -C "$SOURCE" --exclude=./.venv --exclude=./.git --exclude=./results --exclude=./.snakemake \
        --exclude=./.pytest_cache --exclude=./.hypothesis \
        --exclude=./bench/out --exclude=__pycache__ --exclude='*.egg-info' -cf - . | tar -C "$1" -xf -
}

last_jobid() { squeue -t all -h -o %i | sort -n | tail -n 1 | grep . || echo 0; }

# "id|comment|state|CPUs|memory|time limit" of every job submitted after job id $1
jobs_since() { squeue -t all -h -o '%i|%k|%T|%C|%m|%l' | awk -F'|' -v mark="$1" '$1 > mark' | sort -n; }

now() { date +%s.%N; }
elapsed() { awk -v a="$1" -v b="$(now)" 'BEGIN {printf "%.1f", b - a}'; }

# ---------------------------------------------------------------- cluster
T_START=$(now)
slurm_install
slurm_start "$WORK/slurm"
export LUBECONTACT_SLURM_PARTITION=$SLURM_PARTITION   # exercises the profile's partition hook

# Settings for this one-node test cluster only (a real site keeps the profile's values):
# no accounting -> squeue status; quick status polling instead of the plugin's 40 s
# start-up wait; no automatic retry, so that a fault shows.
SLURM_ARGS=(--workflow-profile "$PROFILE" --configfile "$CONFIG" --retries 0
    --slurm-status-command squeue --slurm-init-seconds-before-status-checks 1
    --seconds-between-status-checks 1 --latency-wait 10 --slurm-keep-successful-logs)

# ---------------------------------------------------------------- local reference
copy_workflow "$WORK/local"
LOCAL_PROFILE=none
[ -d "$WORK/local/workflow/profiles/default" ] && LOCAL_PROFILE=workflow/profiles/default
t0=$(now)
smk "$WORK/local" "$WORK/local.log" --workflow-profile "$LOCAL_PROFILE" \
    --configfile "$CONFIG" --cores "$(nproc)" || fail_with_log "the local reference run failed" "$WORK/local.log"
slurm_log "local reference run: $(elapsed "$t0") s"

# ---------------------------------------------------------------- cluster run
copy_workflow "$WORK/cluster"
smk "$WORK/cluster" "$WORK/cluster-plan.log" "${SLURM_ARGS[@]}" --dry-run \
    || fail_with_log "dry run with the SLURM profile failed" "$WORK/cluster-plan.log"
counts=$("$PY" "$HERE/check_results.py" submissions "$WORK/cluster" "$GROUP" <"$WORK/cluster-plan.log")
read -r planned solve_jobs <<<"$counts"
mark=$(last_jobid)
t0=$(now)
smk "$WORK/cluster" "$WORK/cluster.log" "${SLURM_ARGS[@]}" \
    || fail_with_log "the SLURM run failed" "$WORK/cluster.log"
CLUSTER_WALL=$(elapsed "$t0")
jobs_since "$mark" >"$WORK/cluster.jobs"
CLUSTER_SUBMISSIONS=$(wc -l <"$WORK/cluster.jobs")
[ "$CLUSTER_SUBMISSIONS" -gt 0 ] || fail_with_log "the SLURM run submitted no job: did it run locally?" "$WORK/cluster.log"
if awk -F'|' '$3 != "COMPLETED"' "$WORK/cluster.jobs" | grep -q .; then
    slurm_die "SLURM jobs that did not complete: $(awk -F'|' '$3 != "COMPLETED"' "$WORK/cluster.jobs" | tr '\n' ' ')"
fi
# collecting and plotting are light: they must stay local rules, not wait in the queue
if awk -F'|' '$2 ~ /^rule_(collect|plot)(_|$)/' "$WORK/cluster.jobs" | grep -q .; then
    slurm_die "collect/plot jobs went to SLURM (they should be local rules): $(cut -d'|' -f2 "$WORK/cluster.jobs" | sort | uniq -c | tr '\n' ' ')"
fi
[ "$CLUSTER_SUBMISSIONS" = "$planned" ] \
    || slurm_die "$CLUSTER_SUBMISSIONS sbatch submissions, the dry run planned $planned (see $WORK/cluster-plan.log)"
[ "$solve_jobs" -le 1 ] || [ "$CLUSTER_SUBMISSIONS" -lt "$solve_jobs" ] \
    || slurm_die "$solve_jobs solve jobs made $CLUSTER_SUBMISSIONS submissions: not bundled (does every solve rule carry group: \"$GROUP\"?)"
"$PY" "$HERE/check_results.py" compare "$WORK/local/$RESULTS" "$WORK/cluster/$RESULTS" \
    || slurm_die "the SLURM run's results differ from the local run's"
smk "$WORK/cluster" "$WORK/cluster-again.log" "${SLURM_ARGS[@]}" --dry-run \
    || fail_with_log "dry run after the SLURM run failed" "$WORK/cluster-again.log"
grep -q "Nothing to be done" "$WORK/cluster-again.log" \
    || fail_with_log "after the SLURM run Snakemake still has work to do" "$WORK/cluster-again.log"
slurm_log "SLURM run: $CLUSTER_WALL s wall, $CLUSTER_SUBMISSIONS sbatch submissions for $solve_jobs solve jobs, results equal the local run's"
slurm_log "  submitted (CPUs, memory, time limit): $(awk -F'|' '{printf "job %s: %s, %s, %s; ", $1, $4, $5, $6}' "$WORK/cluster.jobs")"

# what the full default study (config/config.yaml, all figures) would submit
smk "$WORK/cluster" "$WORK/full-plan.log" --workflow-profile "$PROFILE" --dry-run \
    || fail_with_log "dry run of the default study with the SLURM profile failed" "$WORK/full-plan.log"
counts=$("$PY" "$HERE/check_results.py" submissions "$WORK/cluster" "$GROUP" <"$WORK/full-plan.log")
read -r full_planned full_solve_jobs <<<"$counts"
slurm_log "default study (all figures): $full_planned sbatch submissions for $full_solve_jobs solve jobs (dry run)"

# ---------------------------------------------------------------- faults
# Both in the cluster run's copy (warm caches), from an empty results directory, one chunk per
# submission so that the other chunks finish. Their targets are the study's solve rules (named
# by the dry run above), which write the case files: not the transient, hysteresis and accuracy
# jobs, which would double each fault run's time and are checked by the SLURM run above.
mapfile -t SOLVE_RULES < <(grep -oP "^\s*rule \K${GROUP}_\w+(?=:)" "$WORK/cluster-plan.log" | sort -u)
[ "${#SOLVE_RULES[@]}" = "$solve_jobs" ] \
    || slurm_die "the dry run names ${#SOLVE_RULES[@]} solve rules for $solve_jobs solve jobs (see $WORK/cluster-plan.log)"
FAULT_ARGS=("${SOLVE_RULES[@]}" "${SLURM_ARGS[@]}" --group-components "$GROUP=1")  # targets first: the options take lists
FAULT_DIR=$WORK/cluster

start_fault_run() {  # log name; sets SMK_PID and RUN_MARK; the partition is down (running_solve_job)
    rm -rf "${FAULT_DIR:?}/$RESULTS"
    RUN_MARK=$(last_jobid)
    scontrol update PartitionName="$SLURM_PARTITION" State=DOWN
    smk_start "$FAULT_DIR" "$WORK/$1.log" "${FAULT_ARGS[@]}"
}

# The solve job of this run with the longest time limit (the most work: solve_resources),
# once it runs. start_fault_run holds the partition down, so every solve job is still
# pending when the victim is chosen: the first job to run may be a chunk of a case or two
# that is written before a fault can reach it, and the largest one may be done before the
# last is submitted. Then the partition comes up and this waits (up to 180 s) for the
# victim to start.
running_solve_job() {
    local id="" state
    for _ in $(seq 900); do
        if [ -z "$id" ]; then
            id=$(squeue -t all -h -o '%i|%k|%l' | awk -F'|' -v mark="$RUN_MARK" -v g="rule_${GROUP}_solve_" -v n="$solve_jobs" '
                function seconds(t,   d, p, k, s, i) {  # SLURM time limit: [D-]H:MM:SS or MM:SS
                    d = 0; if (index(t, "-")) { d = substr(t, 1, index(t, "-") - 1); t = substr(t, index(t, "-") + 1) }
                    k = split(t, p, ":"); s = 0; for (i = 1; i <= k; i++) s = 60 * s + p[i]
                    return 86400 * d + s
                }
                $1 > mark && index($2, g) == 1 { jobs++; l = seconds($3); if (l > best) { best = l; id = $1 } }
                END { if (jobs >= n) print id }')
            [ -n "$id" ] && scontrol update PartitionName="$SLURM_PARTITION" State=UP
        else
            state=$(squeue -h -j "$id" -o %T 2>/dev/null)
            [ "$state" = RUNNING ] && { echo "$id"; return 0; }
        fi
        kill -0 "$SMK_PID" 2>/dev/null || break
        sleep 0.2
    done
    scontrol update PartitionName="$SLURM_PARTITION" State=UP
    return 1
}

wait_first_case() {  # until a case file exists (a chunk is half done) or job $1 stops running, <= 60 s
    for _ in $(seq 600); do
        compgen -G "$FAULT_DIR/$RESULTS/cases/*.nc" >/dev/null && return 0
        [ "$(squeue -h -j "$1" -o %T 2>/dev/null)" = RUNNING ] || return 0
        sleep 0.1
    done
}

case_snapshot() {  # path, inode and checksum of every case file (Snakemake may touch mtimes)
    local f
    for f in "$FAULT_DIR/$RESULTS"/cases/*.nc; do
        if [ -e "$f" ]; then echo "${f##*/} $(stat -c %i "$f") $(md5sum <"$f" | cut -c1-32)"; fi
    done | sort
}

# Rerun after a fault ($1 = name): submits what its dry run plans, keeps every case file
# that was there (same inode and bytes: not solved again, as write_case always makes a new
# file) and completes the study.
rerun_after_fault() {
    local counts planned _ submitted touched
    case_snapshot >"$WORK/$1-before.txt"
    smk "$FAULT_DIR" "$WORK/$1-plan.log" "${FAULT_ARGS[@]}" --dry-run \
        || fail_with_log "$1: dry run of the rerun failed" "$WORK/$1-plan.log"
    counts=$("$PY" "$HERE/check_results.py" submissions "$FAULT_DIR" "$GROUP" <"$WORK/$1-plan.log")
    read -r planned _ <<<"$counts"
    RUN_MARK=$(last_jobid)
    smk "$FAULT_DIR" "$WORK/$1-rerun.log" "${FAULT_ARGS[@]}" \
        || fail_with_log "$1: the rerun failed" "$WORK/$1-rerun.log"
    submitted=$(jobs_since "$RUN_MARK" | wc -l)
    [ "$submitted" = "$planned" ] || slurm_die "$1: the rerun submitted $submitted jobs, its dry run planned $planned"
    touched=$(case_snapshot | comm -13 - "$WORK/$1-before.txt")
    [ -z "$touched" ] || slurm_die "$1: the rerun rewrote case files that were complete: $touched"
    counts=$("$PY" "$HERE/check_results.py" partial "$WORK/local/$RESULTS" "$FAULT_DIR/$RESULTS") \
        || slurm_die "$1: case files after the rerun differ from the local run's"
    read -r RERUN_PRESENT RERUN_MISSING _ <<<"$counts"
    [ "$RERUN_MISSING" = 0 ] || slurm_die "$1: $RERUN_MISSING cases still missing after the rerun"
    RERUN_SUBMISSIONS=$submitted
}

left_cases() {  # $1 = name; sets PRESENT MISSING LEFTOVERS, checks every left case is complete
    local counts
    counts=$("$PY" "$HERE/check_results.py" partial "$WORK/local/$RESULTS" "$FAULT_DIR/$RESULTS") \
        || slurm_die "$1: a case file left behind is not complete"
    read -r PRESENT MISSING LEFTOVERS <<<"$counts"
    [ "$MISSING" -gt 0 ] || slurm_die "$1: no case is missing after the fault: it came too late to bite"
}

if [ "${LUBECONTACT_CLUSTER_FAULT:-1}" = 1 ]; then
    # A: scancel a solve job as soon as it runs; Snakemake stays up, sees it CANCELLED,
    # removes that job's outputs and finishes the other chunks (keep-going).
    t0=$(now)
    start_fault_run fault-a
    victim=$(running_solve_job) || fail_with_log "fault A: no solve job was seen running" "$WORK/fault-a.log"
    scancel "$victim"
    rc=0
    smk_wait || rc=$?
    state=$(squeue -t all -h -j "$victim" -o %T)
    [ "$state" = CANCELLED ] || slurm_die "fault A: job $victim ended $state before the cancel reached it"
    [ "$rc" != 0 ] || fail_with_log "fault A: the run with a cancelled job reported success" "$WORK/fault-a.log"
    submitted=$(jobs_since "$RUN_MARK" | wc -l)
    left_cases "fault A"
    rerun_after_fault fault-a
    [ "$RERUN_SUBMISSIONS" -lt "$submitted" ] \
        || slurm_die "fault A: the rerun resubmitted all $submitted solve jobs, not only the cancelled one"
    slurm_log "fault A (scancel job $victim mid-run): $PRESENT cases kept, all complete, $MISSING missing; rerun: $RERUN_SUBMISSIONS of $submitted submissions, kept cases untouched, all $RERUN_PRESENT cases equal the local run's; $(elapsed "$t0") s"

    # B: the node dies: SIGKILL to Snakemake and to every job of the run, nobody cleans up.
    # Atomic case files must leave only complete cases (temp files are hidden names), and
    # the rerun (rerun-incomplete) must solve only the missing cases of each chunk.
    t0=$(now)
    start_fault_run fault-b
    victim=$(running_solve_job) || fail_with_log "fault B: no solve job was seen running" "$WORK/fault-b.log"
    wait_first_case "$victim"
    kill -KILL "$SMK_PID"
    smk_wait 2>/dev/null || true
    joblist=$(jobs_since "$RUN_MARK" | cut -d'|' -f1 | paste -sd, -)
    [ -n "$joblist" ] || slurm_die "fault B: no job of the run found"
    read -ra ids <<<"${joblist//,/ }"
    slurm_crash_jobs "${ids[@]}"
    scancel "${ids[@]}" 2>/dev/null || true  # the pending ones, and SLURM's bookkeeping
    _slurm_wait 30 sh -c "[ -z \"\$(squeue -h -t RUNNING,COMPLETING -j $joblist)\" ]" \
        || slurm_die "fault B: jobs $joblist still running 30 s after scancel"
    left_cases "fault B"
    smk "$FAULT_DIR" "$WORK/fault-b-unlock.log" "${FAULT_ARGS[@]}" --unlock \
        || fail_with_log "fault B: snakemake --unlock failed" "$WORK/fault-b-unlock.log"
    rerun_after_fault fault-b
    slurm_log "fault B (SIGKILL to Snakemake and jobs $joblist): $PRESENT cases left, all complete, $MISSING missing, $LEFTOVERS temp files; rerun: $RERUN_SUBMISSIONS submissions, kept cases untouched, all $RERUN_PRESENT cases equal the local run's; $(elapsed "$t0") s"
fi

echo "run_slurm: OK: tiny study on SLURM in ${CLUSTER_WALL} s wall with ${CLUSTER_SUBMISSIONS} sbatch submissions ($solve_jobs solve jobs); default study: $full_planned submissions ($full_solve_jobs solve jobs); whole check $(elapsed "$T_START") s"
