#!/bin/bash
# The cluster path, end to end, on a real Slurm: a one-node cluster on loopback, brought
# up here and taken down again.
#
#   tests/slurm/run.sh        (as root on a Debian-like machine; exit 77 = skipped)
#
# It installs Debian's slurmctld, slurmd, slurm-client, munge and parallel if they are
# missing (with a policy-rc.d that stops the packages from starting services), starts
# munged, slurmctld and slurmd as plain background processes on free loopback ports
# with a private key, socket, state and logs, and waits for the node to be idle. Then:
#
#   0. submissions that submit.sh refuses (clashing or missing arguments, abbreviated
#      sbatch options, bouncemap arguments its --check refuses, a missing binary, a
#      partition sbatch rejects) leave no job behind;
#   1. the cluster commands of docs/commands.md, run as written (the blocks marked for this
#      script, with HOME in a scratch directory): a 200-value fig3b sweep in 4 shards
#      through assets/slurm/submit.sh; the merged file must equal the unsharded run but
#      for the provenance's shard line (merged 4/4 for 1/1);
#   2. the same submission again: every shard finds its part complete (--resume) and
#      does no work (the parts are not rewritten), and the merge completes;
#   3. a shard made to fail (its part's path is a directory): the merge job must end,
#      failed, with a message naming the shard; after the cause is removed, the same
#      submission computes only that shard and the merge equals step 1's;
#   4. the workstation commands of docs/commands.md (GNU parallel, and the xargs alternative);
#   5. a small (α, D) plane in 3 shards (800 pixels, so parts of unequal size) through
#      submit.sh: the merged plane.csv must equal the unsharded plane but for the
#      shard line (merged 3/3 for 1/1); submitted again, every shard resumes;
#   6. attractors followed along α in 3 shards through submit.sh (runs of consecutive α
#      values, each after the first from the last value of the one before): the merged
#      attractors.csv must equal the unsharded run's csv, and attractors.txt must say
#      how the parts were joined; submitted again, every shard resumes.
#
# It stops exactly the daemons it started (a zombie counts as stopped) and removes its
# scratch directory. Every wait is bounded; on failure it prints the daemons' and the
# jobs' logs. BOUNCEMAP_SLURM_KEEP=1 keeps the scratch directory.
set -Eeuo pipefail

repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd -P)
# Nothing here may reach another cluster, nor run as a task of one: no SLURM_* from
# the caller (SLURM_CONF points at this test's cluster once it is up).
while read -r v; do unset "$v"; done < <(compgen -e | grep '^SLURM_' || true)
cluster=0 # 1 once SLURM_CONF is this test's own cluster
SKIP=77
say() { echo "slurm test: $*"; }
skip() {
    say "SKIPPED: $*"
    exit "$SKIP"
}

# ------------------------------------------------------------------ prerequisites
[[ $(id -u) -eq 0 ]] || skip "not root (the daemons and the package install need root)"
[[ $(uname -s) == Linux ]] || skip "not Linux"

packages=(slurmctld slurmd slurm-client munge parallel)
commands=(slurmctld slurmd sbatch squeue scontrol sinfo munged munge unmunge parallel setpriv)
missing() {
    local c
    for c in "${commands[@]}"; do
        command -v "$c" >/dev/null || return 0
    done
    return 1
}
if missing; then
    command -v apt-get >/dev/null || skip "the Slurm packages are missing and there is no apt-get to install them"
    say "installing ${packages[*]}"
    # Debian's packages start their services at install unless policy-rc.d says no.
    policy=/usr/sbin/policy-rc.d
    saved=
    if [[ -e $policy ]]; then
        saved=$(mktemp)
        cp -p "$policy" "$saved"
    fi
    printf '#!/bin/sh\n# No services started while the Slurm test installs packages.\nexit 101\n' >"$policy"
    chmod 755 "$policy"
    restore_policy() {
        if [[ -n $saved ]]; then
            cp -p "$saved" "$policy" && rm -f "$saved"
        else
            rm -f "$policy"
        fi
        trap - EXIT
    }
    trap restore_policy EXIT
    apt_log=$(mktemp)
    install() {
        DEBIAN_FRONTEND=noninteractive timeout 900 apt-get install -y -q \
            -o DPkg::Lock::Timeout=300 --no-install-recommends "${packages[@]}" >>"$apt_log" 2>&1
    }
    if ! install; then
        timeout 600 apt-get update -q -o DPkg::Lock::Timeout=300 >>"$apt_log" 2>&1 || true
        if ! install; then
            restore_policy
            tail -n 5 "$apt_log" | sed 's/^/  apt: /'
            rm -f "$apt_log"
            skip "apt-get could not install ${packages[*]}"
        fi
    fi
    restore_policy
    rm -f "$apt_log"
    ! missing || skip "the packages installed, but a command is still missing: ${commands[*]}"
fi

# ------------------------------------------------------------------ the binary
cd "$repo"
target=${CARGO_TARGET_DIR:-$repo/target}
bin=$target/release/bouncemap
say "building the release binary"
cargo build --release --locked -q
[[ -x $bin ]] || {
    say "FAILED: no $bin after cargo build --release"
    exit 1
}
# submit.sh finds target/release/bouncemap beside it; elsewhere it needs BOUNCEMAP.
[[ $target == "$repo/target" ]] || export BOUNCEMAP=$bin

# ------------------------------------------------------------------ scratch and cleanup
work=$(mktemp -d /tmp/bouncemap-slurm.XXXXXX)
chmod 755 "$work" # munged (as the munge user) must reach its socket below it
mkdir -p "$work/log" "$work/home"
pids=()   # the daemons started here, in start order
names=()
stopped=0

state() { # a process's state letter, empty when it is gone
    local s
    s=$(cat "/proc/$1/stat" 2>/dev/null) || return 0
    s=${s##*) }
    echo "${s%% *}"
}

stop_daemons() {
    local i p s deadline
    [[ ${#pids[@]} -gt 0 ]] || return 0
    for ((i = ${#pids[@]} - 1; i >= 0; i--)); do
        p=${pids[i]}
        [[ -n $(state "$p") && $(state "$p") != Z ]] || continue
        kill -TERM "$p" 2>/dev/null || true
        deadline=$((SECONDS + 20))
        while s=$(state "$p") && [[ -n $s && $s != Z ]] && ((SECONDS < deadline)); do
            sleep 0.2
        done
        if [[ -n $s && $s != Z ]]; then
            say "${names[i]} ($p) did not stop on SIGTERM in 20 s: SIGKILL"
            kill -KILL "$p" 2>/dev/null || true
            sleep 1
        fi
    done
    for ((i = 0; i < ${#pids[@]}; i++)); do
        p=${pids[i]}
        s=$(state "$p")
        if [[ -n $s && $s != Z ]]; then
            say "FAILED: ${names[i]} ($p) is still running (state $s)"
            stopped=1
        fi
        wait "$p" 2>/dev/null || true
    done
    pids=()
}

show_logs() {
    local f
    say "---- logs (scratch directory $work)"
    for f in "$work"/log/* "$work"/munge/munged.log; do
        [[ -f $f ]] || continue
        echo "==== $f (last 60 lines)"
        tail -n 60 "$f"
    done
    while IFS= read -r -d '' f; do
        echo "==== $f"
        cat "$f"
    done < <(find "$work/home" "$work/runs" -path '*/logs/*' -type f \( -name '*.log' -o -name submitted \) -print0 2>/dev/null | sort -z)
    if [[ $cluster -eq 1 ]]; then
        echo "==== scontrol show job"
        timeout 10 scontrol show job 2>&1 || true
        echo "==== sinfo"
        timeout 10 sinfo -N -l 2>&1 || true
    fi
}

finish() {
    local rc=$?
    trap - EXIT
    if [[ $rc -ne 0 && $rc -ne $SKIP ]]; then
        show_logs
    fi
    if [[ $cluster -eq 1 ]]; then
        timeout 10 scancel --full --signal=KILL "--user=$(id -un)" 2>/dev/null || true
        timeout 10 scancel "--user=$(id -un)" 2>/dev/null || true
    fi
    stop_daemons
    if [[ $stopped -eq 0 ]]; then
        say "stopped the daemons it started"
    else
        rc=1
    fi
    if [[ ${BOUNCEMAP_SLURM_KEEP:-0} == 1 ]]; then
        say "kept $work"
    else
        rm -rf "$work"
    fi
    exit "$rc"
}
trap finish EXIT
trap 'say "FAILED at line $LINENO: $BASH_COMMAND"' ERR
trap 'exit 130' INT
trap 'exit 143' TERM

fail() {
    say "FAILED: $*"
    exit 1
}

# Wait up to $1 seconds for the command after it to succeed.
wait_for() {
    local limit=$1 what=$2
    shift 2
    local deadline=$((SECONDS + limit))
    until "$@" >/dev/null 2>&1; do
        ((SECONDS < deadline)) || fail "$what: not within $limit s"
        sleep 0.5
    done
}

# Two free TCP ports on this machine (none listens on them, says /proc/net/tcp*).
free_ports() {
    local used=() p n=0 _sl addr _rem st _rest
    while read -r _sl addr _rem st _rest; do
        if [[ $st == 0A ]]; then used+=($((16#${addr##*:}))); fi
    done < <(cat /proc/net/tcp /proc/net/tcp6 2>/dev/null)
    for ((p = 20000 + RANDOM % 20000; n < 2; p++)); do
        if [[ " ${used[*]} " != *" $p "* ]]; then
            echo "$p"
            n=$((n + 1))
        fi
    done
}

# ------------------------------------------------------------------ munge
say "starting munged, slurmctld and slurmd in $work"
m=$work/munge
mkdir -p "$m"
dd if=/dev/urandom of="$m/munge.key" bs=1024 count=1 status=none
chown -R munge:munge "$m"
chmod 755 "$m"
chmod 400 "$m/munge.key"
socket=$m/munge.socket.2
# setpriv execs munged, so $! is munged's PID (runuser would fork).
setpriv --reuid=munge --regid=munge --init-groups \
    munged -F --socket="$socket" --key-file="$m/munge.key" --pid-file="$m/munged.pid" \
    --log-file="$m/munged.log" --seed-file="$m/munged.seed" >"$work/log/munged.out" 2>&1 &
pids+=($!)
names+=(munged)
munge_works() { munge -n --socket="$socket" | unmunge --socket="$socket"; }
wait_for 30 "munged answers on $socket" munge_works

# ------------------------------------------------------------------ slurm
mapfile -t ports < <(free_ports)
ctld_port=${ports[0]} slurmd_port=${ports[1]}
node_line=$(slurmd -C | head -n 1)
[[ $node_line =~ ^NodeName=([^ ]+)\  ]] || fail "slurmd -C printed '$node_line', not a NodeName line"
node=${BASH_REMATCH[1]}
mkdir -p "$work/state" "$work/spool"
cat >"$work/slurm.conf" <<EOF
# One node on loopback, no cgroups, no accounting: the test cluster of tests/slurm/run.sh.
ClusterName=bouncemap-test
SlurmctldHost=$node(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$socket
CredType=cred/munge
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/log/slurmctld.log
SlurmdLogFile=$work/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SchedulerParameters=batch_sched_delay=0
MinJobAge=600
ReturnToService=2
MpiDefault=none
$node_line NodeAddr=127.0.0.1 State=UNKNOWN
PartitionName=test Nodes=$node Default=YES MaxTime=INFINITE State=UP
EOF
export SLURM_CONF=$work/slurm.conf
cluster=1
slurmctld -D -f "$SLURM_CONF" >"$work/log/slurmctld.out" 2>&1 &
pids+=($!)
names+=(slurmctld)
ctld_up() { scontrol ping | grep -q 'is UP'; }
wait_for 60 "slurmctld answers" ctld_up
slurmd -D -f "$SLURM_CONF" >"$work/log/slurmd.out" 2>&1 &
pids+=($!)
names+=(slurmd)
node_idle() { [[ $(sinfo -h -n "$node" -o %T) == idle ]]; }
wait_for 90 "node $node idle" node_idle
say "node $node is idle (slurmctld on port $ctld_port, slurmd on $slurmd_port)"

# ------------------------------------------------------------------ helpers
# Wait until no job is left in the queue (this cluster runs only this test's jobs):
# a merge job that pends for ever fails the wait.
wait_for_jobs() {
    local limit=${1:-300} deadline=$((SECONDS + ${1:-300})) q
    while q=$(squeue -h -o '%i %T %r' 2>&1) && [[ -n $q ]]; do
        if ((SECONDS >= deadline)); then
            say "FAILED: jobs still queued after $limit s:"
            echo "$q"
            exit 1
        fi
        sleep 0.5
    done
}
export -f wait_for_jobs say

# JobState and ExitCode of job $1 (an array job: of each of its tasks).
job_states() { scontrol show job -o "$1" | grep -o 'JobState=[A-Z_]* .* ExitCode=[0-9:]*' | sed -E 's/JobState=([A-Z_]+) .* ExitCode=([0-9:]+)/\1 \2/'; }

# Field $2 (array_job, merge_job) of the submission record in log directory $1.
record() { sed -n "s/^$2=//p" "$1/submitted"; }

# The shell block of docs/commands.md marked `<!-- tests/slurm/run.sh: $1 -->`.
readme_block() {
    awk -v tag="<!-- tests/slurm/run.sh: $1 -->" '
        index($0, tag) { armed = 1; next }
        armed && /^```/ { if (inside) exit; inside = 1; next }
        inside { print }' "$repo/docs/commands.md"
}

# Run the documented lines (and test glue) as a user would type them: in the repository, with
# HOME in the scratch directory. Cargo keeps its own homes.
as_user() {
    local home=$1 script=$2
    (
        export CARGO_HOME=${CARGO_HOME:-$HOME/.cargo} RUSTUP_HOME=${RUSTUP_HOME:-$HOME/.rustup}
        export HOME=$home
        cd "$repo"
        bash -euo pipefail "$script"
    )
}

# Every line of a sweep file but the provenance's shard line.
without_shard() { grep -v '^# shard ' "$1"; }
inode_and_mtime() { stat -c '%i %Y.%y' "$@"; }

the_args=(sweep --preset fig3b --steps 200) # the run docs/commands.md describes
whole=$work/whole.csv
"$bin" "${the_args[@]}" --out "$whole" 2>/dev/null
grep -qx '# shard 1/1' "$whole" || fail "the unsharded file has no '# shard 1/1' line"
# 200 values: indices 0 … 199.
[[ $(grep -v '^#' "$whole" | tail -n +2 | cut -d, -f1 | sort -un | wc -l) -eq 200 ]] ||
    fail "the unsharded file does not hold 200 values"

# Check that $1 (a merged file) is the unsharded run but for `# shard merged 4/4`.
same_as_unsharded() {
    grep -qx '# shard merged 4/4' "$1" || fail "$1 has no '# shard merged 4/4' line"
    diff <(without_shard "$1") <(without_shard "$whole") >/dev/null ||
        fail "$1 differs from the unsharded run beyond its shard line"
}

# ------------------------------------------------------------------ 0. refusals
say "0. submit.sh refuses what it cannot run, and submits nothing"
refuses() { # refuses STATUS MESSAGE ARGUMENT...
    local want=$1 msg=$2 got=0 err
    shift 2
    err=$(PARTS=2 assets/slurm/submit.sh "$work/runs/refused" "$@" 2>&1 >/dev/null) || got=$?
    [[ $got -eq $want ]] || fail "submit.sh $*: status $got, expected $want ($err)"
    grep -qF -- "$msg" <<<"$err" || fail "submit.sh $*: '$err' lacks '$msg'"
}
refuses 2 "no bouncemap arguments after --" --
refuses 2 "'orbit' is not a sharded bouncemap command" -- orbit
refuses 2 "bouncemap argument '--out'" -- sweep --preset fig3b --out x.csv
refuses 2 "bouncemap argument '--shard=1/2'" -- sweep --preset fig3b --shard=1/2
refuses 2 "sbatch option '--array=1-3'" --array=1-3 -- sweep --preset fig3b
refuses 2 "sbatch option '-o'" -o log -- sweep --preset fig3b
refuses 2 "'--part' is not an sbatch option written in full" --part=debug -- sweep --preset fig3b
refuses 2 "bouncemap refused the arguments" -- sweep --preset fig3b --stpes 5
BOUNCEMAP=$work/nowhere refuses 2 "BOUNCEMAP=$work/nowhere is not an executable file" -- sweep
refuses 1 "sbatch refused the shards" --partition=nosuch -- sweep --preset fig3b
[[ -z $(squeue -h) ]] || fail "a refused submission left jobs: $(squeue -h)"
[[ -z $(find "$work/runs/refused" -mindepth 2 -print -quit 2>/dev/null) ]] ||
    fail "a refused submission left files in $work/runs/refused"
say "0. passed"

# ------------------------------------------------------------ 1. the documented commands
submit=$(readme_block cluster-submit)
after=$(readme_block cluster-after)
[[ -n $submit && -n $after ]] || fail "docs/commands.md lacks the blocks marked cluster-submit and cluster-after"
# The glue between the blocks waits for the jobs; at the end it hands back $out.
# shellcheck disable=SC2016 # expanded by the documented shell lines, not here
printf '%s\n' "$submit" wait_for_jobs "$after" 'printf "%s\n" "$out" >"$RESULT"' >"$work/readme-cluster.sh"
say "1. the cluster commands of docs/commands.md"
sed 's/^/  | /' "$work/readme-cluster.sh"
t0=$SECONDS
RESULT=$work/readme-out as_user "$work/home" "$work/readme-cluster.sh" >"$work/log/readme-cluster.out" 2>&1 ||
    {
        cat "$work/log/readme-cluster.out"
        fail "the cluster commands of docs/commands.md failed"
    }
sed 's/^/  > /' "$work/log/readme-cluster.out"
out=$(<"$work/readme-out")
run=$(realpath "$out/logs/latest")
[[ $(tr '\0' '\n' <"$run/args") == "$(printf '%s\n' "${the_args[@]}")" ]] ||
    fail "the documented submission is not '${the_args[*]}'"
array_job=$(record "$run" array_job)
merge_job=$(record "$run" merge_job)
[[ $(job_states "$array_job" | sort | uniq -c | sed 's/^ *//') == "4 COMPLETED 0:0" ]] ||
    fail "the 4 shards did not all complete: $(job_states "$array_job" | tr '\n' ' ')"
[[ $(job_states "$merge_job") == "COMPLETED 0:0" ]] || fail "the merge job: $(job_states "$merge_job")"
for i in 1 2 3 4; do
    grep -qx "# shard $i/4" "$out/part-$i-of-4.csv" || fail "part-$i-of-4.csv is not shard $i/4"
done
same_as_unsharded "$out/sweep.csv"
say "1. passed in $((SECONDS - t0)) s: 4 shards merged into the unsharded file (but 'merged 4/4' for '1/1')"

# ------------------------------------------------------------------ 2. resume
say "2. the same submission again: every shard is already there"
t0=$SECONDS
before=$(inode_and_mtime "$out"/part-*-of-4.csv)
merged=$(cat "$out/sweep.csv")
printf '%s\n' "$submit" wait_for_jobs >"$work/readme-again.sh"
as_user "$work/home" "$work/readme-again.sh" >"$work/log/readme-again.out" 2>&1 ||
    {
        cat "$work/log/readme-again.out"
        fail "submitting again failed"
    }
run=$(realpath "$out/logs/latest")
[[ $(inode_and_mtime "$out"/part-*-of-4.csv) == "$before" ]] || fail "a part was rewritten"
for i in 1 2 3 4; do
    log=$run/shard-$i.log
    grep -q "already holds shard $i/4 of this sweep" "$log" || fail "shard $i did not resume: $log"
    ! grep -q 'sweep of .* values started' "$log" || fail "shard $i computed: $log"
done
[[ $(job_states "$(record "$run" array_job)" | sort | uniq -c | sed 's/^ *//') == "4 COMPLETED 0:0" ]] ||
    fail "the resumed shards did not all complete"
[[ $(job_states "$(record "$run" merge_job)") == "COMPLETED 0:0" ]] || fail "the second merge job did not complete"
[[ $(cat "$out/sweep.csv") == "$merged" ]] || fail "the second merge differs from the first"
say "2. passed in $((SECONDS - t0)) s: no shard recomputed or rewrote its part"

# ------------------------------------------------------------------ 3. a failed shard
say "3. a shard that fails: its part's path is a directory"
t0=$SECONDS
fails=$work/runs/fails
mkdir -p "$fails/part-3-of-4.csv"
PARTS=4 assets/slurm/submit.sh "$fails" -- "${the_args[@]}" >"$work/log/fails-submit.out"
wait_for_jobs 300
run=$(realpath "$fails/logs/latest")
merge_job=$(record "$run" merge_job)
states=$(job_states "$(record "$run" array_job)" | sort | tr '\n' ' ')
[[ $states == "COMPLETED 0:0 COMPLETED 0:0 COMPLETED 0:0 FAILED 2:0 " ]] ||
    fail "shards: $states, expected three completed and one failed"
grep -q 'cannot create .*part-3-of-4.csv: it is a directory' "$run/shard-3.log" ||
    fail "shard 3's log does not say why it failed"
[[ $(job_states "$merge_job") == "FAILED 2:0" ]] ||
    fail "the merge job after a failed shard: $(job_states "$merge_job"), expected FAILED 2:0"
grep -q 'missing shard 3/4' "$run/merge.log" || fail "the merge log does not name shard 3/4"
[[ ! -e $fails/sweep.csv ]] || fail "a merged file was written without shard 3"
say "   the merge job ended (FAILED) naming the shard: $(grep -m1 'missing shard' "$run/merge.log")"
rmdir "$fails/part-3-of-4.csv"
before=$(inode_and_mtime "$fails"/part-{1,2,4}-of-4.csv)
PARTS=4 assets/slurm/submit.sh "$fails" -- "${the_args[@]}" >"$work/log/fails-again.out"
wait_for_jobs 300
run=$(realpath "$fails/logs/latest")
[[ $(inode_and_mtime "$fails"/part-{1,2,4}-of-4.csv) == "$before" ]] || fail "a finished part was rewritten"
grep -q 'sweep of 50 values started' "$run/shard-3.log" || fail "shard 3 was not computed"
[[ $(job_states "$(record "$run" merge_job)") == "COMPLETED 0:0" ]] || fail "the merge after the fix did not complete"
cmp -s "$fails/sweep.csv" "$out/sweep.csv" || fail "the repaired run differs from step 1's"
say "3. passed in $((SECONDS - t0)) s: resubmitted, only shard 3 was computed"

# ------------------------------------------------------------------ 4. workstation
say "4. the workstation commands of docs/commands.md"
t0=$SECONDS
local_block=$(readme_block workstation)
xargs_line=$(readme_block workstation-xargs)
[[ -n $local_block && -n $xargs_line ]] || fail "docs/commands.md lacks the blocks marked workstation and workstation-xargs"
grep -q '^parallel ' <<<"$local_block" || fail "the workstation block has no parallel line"
for tool in parallel xargs; do
    if [[ $tool == parallel ]]; then
        printf '%s\n' "$local_block" >"$work/readme-$tool.sh"
    else
        while IFS= read -r line; do
            if [[ $line == parallel\ * ]]; then printf '%s\n' "$xargs_line"; else printf '%s\n' "$line"; fi
        done <<<"$local_block" >"$work/readme-$tool.sh"
    fi
    # shellcheck disable=SC2016 # expanded by the documented shell lines, not here
    printf '%s\n' 'printf "%s\n" "$PWD" >"$RESULT"' >>"$work/readme-$tool.sh"
    sed 's/^/  | /' "$work/readme-$tool.sh"
    mkdir -p "$work/home-$tool"
    RESULT=$work/$tool-out as_user "$work/home-$tool" "$work/readme-$tool.sh" >"$work/log/readme-$tool.out" 2>&1 ||
        {
            cat "$work/log/readme-$tool.out"
            fail "the workstation commands of docs/commands.md ($tool) failed"
        }
    dir=$(<"$work/$tool-out")
    same_as_unsharded "$dir/sweep.csv"
done
say "4. passed in $((SECONDS - t0)) s: GNU parallel and xargs shards merged into the unsharded file"

# ------------------------------------------------------------------ 5. a plane
say "5. a plane through submit.sh"
t0=$SECONDS
plane_args=(plane --table fd --x alpha:0.45..0.60 --y d:0..1 --r 0.8 --size 40x20 --transient 2000)
plane_whole=$work/plane-whole.csv
"$bin" "${plane_args[@]}" --format csv --out "$plane_whole" 2>/dev/null
grep -qx '# shard 1/1' "$plane_whole" || fail "the unsharded plane has no '# shard 1/1' line"
[[ $(grep -v '^#' "$plane_whole" | tail -n +2 | wc -l) -eq 800 ]] ||
    fail "the unsharded plane does not hold 800 pixels"
planes=$work/runs/plane
PARTS=3 assets/slurm/submit.sh "$planes" -- "${plane_args[@]}" >"$work/log/plane-submit.out"
wait_for_jobs 300
run=$(realpath "$planes/logs/latest")
[[ $(job_states "$(record "$run" array_job)" | sort | uniq -c | sed 's/^ *//') == "3 COMPLETED 0:0" ]] ||
    fail "the 3 plane shards did not all complete: $(job_states "$(record "$run" array_job)" | tr '\n' ' ')"
[[ $(job_states "$(record "$run" merge_job)") == "COMPLETED 0:0" ]] ||
    fail "the plane's merge job: $(job_states "$(record "$run" merge_job)")"
# 800 pixels in 3 parts: 267, 267 and 266 rows.
for i in 1 2 3; do
    grep -qx "# shard $i/3" "$planes/part-$i-of-3.csv" || fail "part-$i-of-3.csv is not shard $i/3"
    grep -q "plane of $((i < 3 ? 267 : 266)) pixels started" "$run/shard-$i.log" ||
        fail "shard $i did not compute its $((i < 3 ? 267 : 266)) pixels: $run/shard-$i.log"
done
grep -qx '# shard merged 3/3' "$planes/plane.csv" || fail "plane.csv has no '# shard merged 3/3' line"
diff <(without_shard "$planes/plane.csv") <(without_shard "$plane_whole") >/dev/null ||
    fail "the merged plane differs from the unsharded plane beyond its shard line"
before=$(inode_and_mtime "$planes"/part-*-of-3.csv)
merged=$(cat "$planes/plane.csv")
PARTS=3 assets/slurm/submit.sh "$planes" -- "${plane_args[@]}" >"$work/log/plane-again.out"
wait_for_jobs 300
run=$(realpath "$planes/logs/latest")
[[ $(inode_and_mtime "$planes"/part-*-of-3.csv) == "$before" ]] || fail "a plane part was rewritten"
for i in 1 2 3; do
    grep -q "already holds shard $i/3 of this plane" "$run/shard-$i.log" ||
        fail "plane shard $i did not resume: $run/shard-$i.log"
done
[[ $(job_states "$(record "$run" merge_job)") == "COMPLETED 0:0" ]] || fail "the plane's second merge job did not complete"
[[ $(cat "$planes/plane.csv") == "$merged" ]] || fail "the plane's second merge differs from the first"
say "5. passed in $((SECONDS - t0)) s: 3 plane shards merged into the unsharded plane, and resumed"

# ------------------------------------------------------------------ 6. attractors
say "6. attractors along α through submit.sh"
t0=$SECONDS
att_args=(attractors --table cubic --alpha 0.46..0.5 --steps 12 --grid 30x30)
att_whole=$work/attractors-whole.csv
"$bin" "${att_args[@]}" --format csv --out "$att_whole" 2>/dev/null
atts=$work/runs/attractors
PARTS=3 assets/slurm/submit.sh "$atts" -- "${att_args[@]}" >"$work/log/attractors-submit.out"
wait_for_jobs 300
run=$(realpath "$atts/logs/latest")
[[ $(job_states "$(record "$run" array_job)" | sort | uniq -c | sed 's/^ *//') == "3 COMPLETED 0:0" ]] ||
    fail "the 3 attractors shards did not all complete: $(job_states "$(record "$run" array_job)" | tr '\n' ' ')"
[[ $(job_states "$(record "$run" merge_job)") == "COMPLETED 0:0" ]] ||
    fail "the attractors' merge job: $(job_states "$(record "$run" merge_job)")"
# 12 values in 3 parts: 4, then 4 + the value before each (5 pictures of 900 starts).
for i in 1 2 3; do
    starts=$((i == 1 ? 3600 : 4500))
    grep -q "attractors of $starts starts started" "$run/shard-$i.log" ||
        fail "shard $i did not compute its $starts starts: $run/shard-$i.log"
done
cmp -s "$atts/attractors.csv" "$att_whole" ||
    fail "the merged attractors.csv differs from the unsharded run's csv"
grep -q '^merged from 3 parts' "$atts/attractors.txt" || fail "attractors.txt does not say it was merged from 3 parts"
[[ $(grep -c 'the two pictures agree on every basin fraction' "$atts/attractors.txt") -eq 2 ]] ||
    fail "attractors.txt does not show both joins agreeing: $atts/attractors.txt"
before=$(inode_and_mtime "$atts"/part-*-of-3.json)
PARTS=3 assets/slurm/submit.sh "$atts" -- "${att_args[@]}" >"$work/log/attractors-again.out"
wait_for_jobs 300
run=$(realpath "$atts/logs/latest")
[[ $(inode_and_mtime "$atts"/part-*-of-3.json) == "$before" ]] || fail "an attractors part was rewritten"
for i in 1 2 3; do
    grep -q "already holds shard $i/3 of this attractors run" "$run/shard-$i.log" ||
        fail "attractors shard $i did not resume: $run/shard-$i.log"
done
[[ $(job_states "$(record "$run" merge_job)") == "COMPLETED 0:0" ]] || fail "the attractors' second merge job did not complete"
cmp -s "$atts/attractors.csv" "$att_whole" || fail "the second merge differs from the unsharded run's csv"
say "6. passed in $((SECONDS - t0)) s: 3 attractors shards joined into the unsharded run, and resumed"

say "PASSED"
