#!/bin/bash
# The merge job of a run submitted by submit.sh (see there): once every shard has ended
# (successfully or not), join OUT_DIR/part-1-of-PARTS.csv ... into OUT_DIR/COMMAND.csv
# (sweep.csv for a sweep, plane.csv for a plane); the json parts of attractors into its
# report, OUT_DIR/attractors.txt and OUT_DIR/attractors.csv.
# A shard without its part makes `bouncemap merge` fail naming it; the job then fails.
# Arguments: the submission's log directory, PARTS.
set -euo pipefail

run=$1
parts=$2
echo "bouncemap merge of $parts shards: job ${SLURM_JOB_ID:-?} on $(hostname), $(date -Is)"
bin=$(<"$run/bouncemap")
out_dir=$(<"$run/out_dir")
mapfile -d '' -t args <"$run/args"
part_ext=$(<"$run/part_ext")
[[ -x $bin ]] || {
    echo "bouncemap merge: the binary $bin is not on $(hostname): it must be on a filesystem every node shares" >&2
    exit 1
}

files=()
missing=()
for ((i = 1; i <= parts; i++)); do
    f=$out_dir/part-$i-of-$parts.$part_ext
    if [[ -f $f ]]; then
        files+=("$f")
    else
        missing+=("$i/$parts")
        echo "bouncemap merge: shard $i/$parts has no part file $f: see $run/shard-$i.log" >&2
    fi
done
if [[ ${#files[@]} -eq 0 ]]; then
    echo "bouncemap merge: missing shards ${missing[*]}: no shard wrote its part" >&2
    exit 1
fi
merge() { # merge RESULT [FLAG...]
    local result=$1
    shift
    local cmd=("$bin" merge "${files[@]}" "$@" --out "$result")
    printf 'running:'
    printf ' %q' "${cmd[@]}"
    echo
    "${cmd[@]}"
    echo "bouncemap merge: merged ${#files[@]} parts into $result"
}
if [[ ${args[0]} == attractors ]]; then
    merge "$out_dir/attractors.txt" --format text
    merge "$out_dir/attractors.csv" --format csv
else
    merge "$out_dir/${args[0]}.csv"
fi
