#!/bin/bash
# One shard of a run submitted by submit.sh (see there): array task I of 1-PARTS runs
# bouncemap with the stored arguments and --shard auto --resume (and what submit.sh
# stored for the command: --format csv for sweep and plane), writing
# OUT_DIR/part-I-of-PARTS.csv (.json for attractors). Arguments: the submission's log
# directory, PARTS.
set -euo pipefail

run=$1
parts=$2
task=${SLURM_ARRAY_TASK_ID:?not a task of a job array: submit with submit.sh}
echo "bouncemap shard $task/$parts: job ${SLURM_ARRAY_JOB_ID:-?}_$task on $(hostname), $(date -Is)"

fail() {
    echo "bouncemap shard $task/$parts: $*" >&2
    exit 1
}

[[ -r $run/args ]] || fail "$run/args is not readable on $(hostname): OUT_DIR must be on a filesystem every node shares"
bin=$(<"$run/bouncemap")
out_dir=$(<"$run/out_dir")
mapfile -d '' -t args <"$run/args"
mapfile -d '' -t part_flags <"$run/part_flags"
part_ext=$(<"$run/part_ext")
[[ -x $bin ]] || fail "the binary $bin is not on $(hostname): it must be on a filesystem every node shares (or set BOUNCEMAP at submission)"
# --shard auto takes I/N from the array's bounds; they must be the submitted 1-PARTS,
# or the part would not be the one this file is named after.
[[ ${SLURM_ARRAY_TASK_MIN:-} == 1 && ${SLURM_ARRAY_TASK_MAX:-} == "$parts" ]] ||
    fail "the array is ${SLURM_ARRAY_TASK_MIN:-?}-${SLURM_ARRAY_TASK_MAX:-?}, not 1-$parts: submit again with submit.sh (finished shards are skipped)"

part=$out_dir/part-$task-of-$parts.$part_ext
cmd=("$bin" "${args[@]}" --shard auto --resume "${part_flags[@]}" --out "$part")
printf 'running:'
printf ' %q' "${cmd[@]}"
echo
exec "${cmd[@]}"
