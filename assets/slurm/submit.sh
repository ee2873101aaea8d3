#!/bin/bash
# Submit one sharded bouncemap run to Slurm: a job array of PARTS shards, then a job
# that merges them once every shard has ended.
#
#   [PARTS=N] [BOUNCEMAP=PATH] assets/slurm/submit.sh OUT_DIR [SBATCH_OPTION...] -- COMMAND [ARGUMENT...]
#
#   PARTS=4 assets/slurm/submit.sh ~/runs/fig3b --time=00:30:00 -- sweep --preset fig3b
#
# COMMAND is a sharded bouncemap command (sweep, plane or attractors) and ARGUMENTs are
# its arguments, passed to it exactly as given (stored at submission, never word-split).
# The script adds --shard auto --resume --format csv --out OUT_DIR/part-I-of-N.csv
# itself (for attractors --shard auto --resume --out OUT_DIR/part-I-of-N.json, its
# parts being json), so ARGUMENTs must not contain --shard, --resume, --format or --out.
#
# Shard I (array task I of 1-N) writes OUT_DIR/part-I-of-N.csv (.json); the merge job
# writes OUT_DIR/COMMAND.csv (sweep.csv, plane.csv), identical to the unsharded run but
# for its provenance's shard line (merged N/N); for attractors the report of the whole
# window, OUT_DIR/attractors.txt and OUT_DIR/attractors.csv, with a line per join in the
# text. A failed shard makes the merge job fail with a message naming the
# missing shard; submitting the same command again recomputes only the shards that are
# missing (--resume leaves complete, verified parts alone).
#
# Variables:
#   PARTS      number of shards (array tasks 1-PARTS) [4]
#   BOUNCEMAP  the bouncemap binary; else the build beside this script
#              (target/release/bouncemap of this checkout), else bouncemap on PATH.
#              Resolved to an absolute path now, and checked to run.
#
# SBATCH_OPTIONs (--partition, --account, --time, --cpus-per-task, --mem, ...) go to
# both jobs, after the defaults --nodes=1 --ntasks=1 --cpus-per-task=1
# --job-name=bouncemap-COMMAND, so they override them; the merge job runs on one CPU.
# Each must be an sbatch option written in full (--partition=debug, --time 1:00:00,
# -p debug): abbreviations and unknown options are refused, as are those this script
# sets itself (--array, --dependency, --output, --error, --wrap, --parsable, --chdir).
#
# Before anything is queued the bouncemap arguments are checked: the first shard's
# command runs with --check (parse, validate, print the plan, compute nothing), and a
# refusal ends the submission with bouncemap's one-line message.
# No --time is set: the partition's default applies unless you give one. A shard's
# worker threads are its --cpus-per-task (SLURM_CPUS_PER_TASK).
#
# OUT_DIR, the binary and any file named in the ARGUMENTs must be on a filesystem that
# the submit host and every compute node share (home or scratch, not /tmp). Relative
# paths in the ARGUMENTs are relative to the directory you submit from.
#
# OUT_DIR/logs/<submission>/ records what ran: the arguments (args, NUL-separated),
# the binary and its version, the job ids (submitted), and the jobs' logs
# (shard-I.log, merge.log); OUT_DIR/logs/latest points to the newest submission.
set -euo pipefail

me=${0##*/}
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd -P)

die() {
    echo "$me: $*" >&2
    exit 2
}

usage="usage: [PARTS=N] $me OUT_DIR [SBATCH_OPTION...] -- COMMAND [ARGUMENT...]"
[[ $# -ge 1 && $1 != -* ]] || die "no OUT_DIR: $usage"
out_dir=$1
shift
sbatch_opts=()
while [[ $# -gt 0 && $1 != -- ]]; do
    sbatch_opts+=("$1")
    shift
done
[[ $# -gt 0 ]] || die "no -- before the bouncemap arguments: $usage"
shift
[[ $# -gt 0 ]] || die "no bouncemap arguments after --: $usage"
args=("$@")

# The options this script sets itself.
for o in "${sbatch_opts[@]}"; do
    case $o in
    --array | --array=* | -a | -a?*) die "sbatch option '$o': the array is 1-PARTS; set PARTS instead" ;;
    --dependency | --dependency=* | -d | -d?*) die "sbatch option '$o': the merge job's dependency is set by this script" ;;
    --output | --output=* | -o | -o?* | --error | --error=* | -e | -e?*)
        die "sbatch option '$o': the logs go to OUT_DIR/logs/" ;;
    --wrap | --wrap=*) die "sbatch option '$o': this script submits its own batch scripts" ;;
    --parsable | --test-only | --wait | -W | --help | -h | --usage | --version | -V)
        die "sbatch option '$o': this script submits and reports the jobs itself" ;;
    --chdir | --chdir=* | -D | -D?*)
        die "sbatch option '$o': the jobs run where you submit from (relative paths in the arguments are relative to it)" ;;
    esac
done

# Every other option must be one sbatch has, written in full: sbatch takes any
# unambiguous abbreviation (--arr, --dep, --out), which would slip past the checks above,
# and an unknown option would be found only by sbatch. Options that take a value take it
# as --NAME=VALUE or as the next word (-X VALUE or -XVALUE for a short one).
with_value=" account acctg-freq begin bb bbf clusters cluster-constraint comment constraint
 container container-id core-spec cores-per-socket cpu-freq cpus-per-gpu cpus-per-task
 deadline delay-boot distribution exclude export export-file extra extra-node-info gid
 gpu-bind gpu-freq gpus gpus-per-node gpus-per-socket gpus-per-task gres gres-flags hint
 input job-name licenses mail-type mail-user mcs-label mem mem-bind mem-per-cpu
 mem-per-gpu mincpus network nice nodefile nodelist nodes ntasks ntasks-per-core
 ntasks-per-gpu ntasks-per-node ntasks-per-socket open-mode partition power prefer
 priority profile propagate qos reservation signal sockets-per-node switches thread-spec
 threads-per-core time time-min tmp tres-per-task uid wckey "
flags=" contiguous exclusive get-user-env hold ignore-pbs kill-on-invalid-dep no-kill
 no-requeue overcommit oversubscribe quiet reboot requeue spread-job use-min-nodes verbose
 wait-all-nodes "
short_with_value="ACcGiJLMmNnpqSbtwxF"
short_flags="HkOQsv"
i=0
while ((i < ${#sbatch_opts[@]})); do
    o=${sbatch_opts[i]}
    case $o in
    --*=*)
        name=${o%%=*}
        name=${name#--}
        [[ $with_value == *" $name "* || $flags == *" $name "* ]] ||
            die "sbatch option '$o': '--$name' is not an sbatch option written in full: valid the full names of sbatch --help (e.g. --partition, --time, --cpus-per-task, --mem)"
        ;;
    --?*)
        name=${o#--}
        if [[ $with_value == *" $name "* ]]; then
            ((i + 1 < ${#sbatch_opts[@]})) || die "sbatch option '$o' needs a value: valid $o=VALUE"
            i=$((i + 1))
        elif [[ $flags != *" $name "* ]]; then
            die "sbatch option '$o': not an sbatch option written in full: valid the full names of sbatch --help (e.g. --partition, --time, --cpus-per-task, --mem)"
        fi
        ;;
    -?*)
        letter=${o:1:1}
        if [[ $short_with_value == *"$letter"* ]]; then
            if [[ ${#o} -eq 2 ]]; then
                ((i + 1 < ${#sbatch_opts[@]})) || die "sbatch option '$o' needs a value: valid $o VALUE"
                i=$((i + 1))
            fi
        elif [[ $short_flags != *"$letter"* || ${#o} -ne 2 ]]; then
            die "sbatch option '$o': not an sbatch option this script passes on: valid e.g. -p PARTITION, -t TIME, -c CPUS, or a full --NAME=VALUE"
        fi
        ;;
    *) die "'$o' is not an sbatch option (before --): valid --NAME=VALUE, --NAME VALUE, -X VALUE; the bouncemap arguments go after --" ;;
    esac
    i=$((i + 1))
done
# What a shard adds to the arguments besides --shard auto --resume --out, and its
# part's extension (stored for shard.sh and merge.sh).
case ${args[0]} in
sweep | plane) part_flags=(--format csv) part_ext=csv ;;
attractors) part_flags=() part_ext=json ;;
*) die "'${args[0]}' is not a sharded bouncemap command: valid sweep, plane or attractors" ;;
esac
for a in "${args[@]:1}"; do
    case $a in
    --shard | --shard=* | --resume | --resume=* | --format | --format=* | --out | --out=*)
        die "bouncemap argument '$a': this script sets --shard auto --resume ${part_flags[*]:+${part_flags[*]} }--out OUT_DIR/part-I-of-N.$part_ext itself" ;;
    esac
done

parts=${PARTS:-4}
[[ $parts =~ ^[1-9][0-9]*$ ]] || die "PARTS='$parts' is not a number of shards: valid 1, 2, 3, ..."

command -v sbatch >/dev/null || die "sbatch not found: run this on a host that submits Slurm jobs"

# The binary, by absolute path, checked to run.
if [[ -n ${BOUNCEMAP:-} ]]; then
    bin=$BOUNCEMAP
    [[ -f $bin && -x $bin ]] || die "BOUNCEMAP=$bin is not an executable file"
elif [[ -x $here/../../target/release/bouncemap ]]; then
    bin=$here/../../target/release/bouncemap
elif command -v bouncemap >/dev/null; then
    bin=$(command -v bouncemap)
else
    die "no bouncemap binary: set BOUNCEMAP=/path/to/bouncemap, or build one with 'cargo build --release' in this checkout, or put bouncemap on PATH"
fi
bin=$(realpath -- "$bin")
version=$("$bin" --version 2>&1) || die "$bin does not run here: $version"

mkdir -p -- "$out_dir" || die "cannot create OUT_DIR $out_dir"
out_dir=$(realpath -- "$out_dir")

# The bouncemap arguments checked before anything is queued: the same command the first
# shard runs, as a dry run (--check: every flag, file and the part's path checked, the
# plan printed, nothing computed). A typo is refused here, not on the nodes.
check=("$bin" "${args[@]}" --shard "1/$parts" --resume "${part_flags[@]}" --out "$out_dir/part-1-of-$parts.$part_ext" --check)
plan=$("${check[@]}" 2>&1) || die "bouncemap refused the arguments, nothing was submitted: $(tail -n 1 <<<"$plan")"
sed "s/^/$me: /" <<<"$plan"
stamp=$(date +%Y%m%d-%H%M%S)-$$
run=$out_dir/logs/$stamp
mkdir -p -- "$run"
printf '%s\0' "${args[@]}" >"$run/args"
printf '%s\n' "$bin" >"$run/bouncemap"
printf '%s\n' "$out_dir" >"$run/out_dir"
# (printf with no arguments would still write one empty one)
if ((${#part_flags[@]})); then printf '%s\0' "${part_flags[@]}"; fi >"$run/part_flags"
printf '%s\n' "$part_ext" >"$run/part_ext"

# sbatch expands %-patterns in log paths: a literal % is %%.
logs=${run//%/%%}
defaults=(--nodes=1 --ntasks=1 --cpus-per-task=1 "--job-name=bouncemap-${args[0]}")
array_job=$(sbatch --parsable "${defaults[@]}" "${sbatch_opts[@]}" \
    --array="1-$parts" --output="$logs/shard-%a.log" \
    "$here/shard.sh" "$run" "$parts") || {
    echo "$me: sbatch refused the shards (its message is above); nothing was submitted" >&2
    rm -rf -- "$run"
    exit 1
}
array_job=${array_job%%;*}
merge_job=$(sbatch --parsable "${defaults[@]}" "${sbatch_opts[@]}" --cpus-per-task=1 \
    --dependency="afterany:$array_job" --kill-on-invalid-dep=yes --output="$logs/merge.log" \
    "$here/merge.sh" "$run" "$parts") || {
    echo "$me: sbatch refused the merge job (its message is above); cancelling the shards, job $array_job" >&2
    scancel "$array_job" || true
    exit 1
}
merge_job=${merge_job%%;*}
ln -sfn "$stamp" "$out_dir/logs/latest"

{
    echo "submitted $(date -Is) from $(hostname) in $PWD"
    echo "bouncemap: $bin ($version)"
    printf 'arguments:'
    printf ' %q' "${args[@]}"
    echo
    printf 'sbatch options:'
    printf ' %q' "${defaults[@]}" "${sbatch_opts[@]}"
    echo
    echo "parts: $parts"
    echo "array_job=$array_job"
    echo "merge_job=$merge_job"
} >"$run/submitted"

echo "$me: shards 1-$parts as job array $array_job, merge as job $merge_job (once every shard has ended)"
if [[ ${args[0]} == attractors ]]; then
    echo "$me: logs in $run; the merged report will be $out_dir/attractors.txt and $out_dir/attractors.csv"
else
    echo "$me: logs in $run; the merged file will be $out_dir/${args[0]}.csv"
fi
