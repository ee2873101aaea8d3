#!/bin/bash
# Run one large bouncemap sweep as a Slurm job array of N parts, then merge.
#
#   sbatch --array=1-8 assets/slurm/sweep-array.sh            # the 8 parts
#   sbatch --dependency=afterok:<JOBID> --export=ALL,MERGE=1 \
#          assets/slurm/sweep-array.sh                          # join them
#
# Each array task computes the interleaved part I/N (I = SLURM_ARRAY_TASK_ID,
# N = SLURM_ARRAY_TASK_COUNT) on all cores of its node and writes
# $OUT_DIR/part-I-of-N.csv; the merge step writes $OUT_DIR/sweep.csv, identical
# to the unsharded run. Edit SWEEP_ARGS for the sweep you want.
#SBATCH --job-name=bouncemap-sweep
#SBATCH --nodes=1
#SBATCH --ntasks=1
#SBATCH --cpus-per-task=32
#SBATCH --time=04:00:00
#SBATCH --output=bouncemap-sweep-%A_%a.log

set -euo pipefail

BOUNCEMAP=${BOUNCEMAP:-bouncemap}
OUT_DIR=${OUT_DIR:-sweep-out}
SWEEP_ARGS=${SWEEP_ARGS:---preset fig3b}
PARTS=${PARTS:-${SLURM_ARRAY_TASK_COUNT:-8}}

mkdir -p "$OUT_DIR"

if [[ "${MERGE:-0}" == "1" ]]; then
    files=()
    for i in $(seq 1 "$PARTS"); do
        files+=("$OUT_DIR/part-$i-of-$PARTS.csv")
    done
    "$BOUNCEMAP" merge "${files[@]}" --out "$OUT_DIR/sweep.csv"
    echo "merged $PARTS parts into $OUT_DIR/sweep.csv"
    exit 0
fi

I=${SLURM_ARRAY_TASK_ID:?run as a job array: sbatch --array=1-N}
# shellcheck disable=SC2086 # SWEEP_ARGS is a list of flags
"$BOUNCEMAP" sweep $SWEEP_ARGS \
    --threads "${SLURM_CPUS_PER_TASK:-1}" \
    --shard "$I/$PARTS" \
    --format csv --out "$OUT_DIR/part-$I-of-$PARTS.csv"
