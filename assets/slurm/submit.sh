#!/bin/bash
# Submit one sharded bouncemap run to Slurm: a job array of PARTS shards, then a job
# that merges them once every shard has ended.
#
#   [PARTS=N] [BOUNCEMAP=PATH] assets/slurm/submit.sh OUT_DIR [SBATCH_OPTION...] -- COMMAND [ARGUMENT...]
#
#   PARTS=4 assets/slurm/submit.sh ~/runs/fig3b --time=00:30:00 -- sweep --preset fig3b
#
# COMMAND is a sharded bouncemap command (sweep or plane) and ARGUMENTs are its
# arguments, passed to it exactly as given (stored at submission, never word-split).
# The script adds --shard auto --resume --format csv --out OUT_DIR/part-I-of-N.csv
# itself, so ARGUMENTs must not contain --shard, --resume, --format or --out.
#
# Shard I (array task I of 1-N) writes OUT_DIR/part-I-of-N.csv; the merge job writes
# OUT_DIR/COMMAND.csv (sweep.csv, plane.csv), identical to the unsharded run but for its provenance's shard
# line (merged N/N). A failed shard makes the merge job fail with a message naming the
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
    esac
done
case ${args[0]} in
sweep | plane) ;;
*) die "'${args[0]}' is not a sharded bouncemap command: valid sweep or plane" ;;
esac
for a in "${args[@]:1}"; do
    case $a in
    --shard | --shard=* | --resume | --resume=* | --format | --format=* | --out | --out=*)
        die "bouncemap argument '$a': this script sets --shard auto --resume --format csv --out OUT_DIR/part-I-of-N.csv itself" ;;
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
stamp=$(date +%Y%m%d-%H%M%S)-$$
run=$out_dir/logs/$stamp
mkdir -p -- "$run"
printf '%s\0' "${args[@]}" >"$run/args"
printf '%s\n' "$bin" >"$run/bouncemap"
printf '%s\n' "$out_dir" >"$run/out_dir"

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
echo "$me: logs in $run; the merged file will be $out_dir/${args[0]}.csv"
