#!/usr/bin/env bash
# A tightrope batch as a SLURM job array: task I of J tightens the knots at places I, I+J, ...
# of the manifest (tightrope batch --job I --jobs J) into the shared output folder, with one
# device each; every task rewrites OUT/table.tsv and table.json under a lock, so the last one
# to finish leaves the whole table (tightrope batch MANIFEST -o OUT --table-only rebuilds it).
#
#   K=$(tightrope batch MANIFEST --list | wc -l)         # one task per knot, or fewer
#   sbatch --array=0-$((K - 1)) scripts/slurm_batch.sh MANIFEST OUT [BATCH-OPTIONS] [-- TIGHTEN-OPTIONS...]
#   sbatch --array=0-$((K - 1)) --gres=gpu:1 scripts/slurm_batch.sh ...   # a GPU per task
#
# A task that is killed or requeued resumes its knot from the checkpoint in OUT when it runs
# again (knots already done are skipped), so resubmitting the same array finishes the table.
# The array's indices must be contiguous (0-9, 1-10, 0-34%4: at most 4 at once), since
# I = SLURM_ARRAY_TASK_ID - SLURM_ARRAY_TASK_MIN and J = SLURM_ARRAY_TASK_COUNT. OUT must be
# on a file system every node sees. TIGHTROPE names the binary (default: tightrope on PATH).
#SBATCH --job-name=tightrope-batch
#SBATCH --ntasks=1
#SBATCH --cpus-per-task=1
#SBATCH --output=tightrope-batch-%A_%a.out
set -euo pipefail
if [ $# -lt 2 ]; then
  echo "usage: sbatch --array=0-K scripts/slurm_batch.sh MANIFEST OUT [BATCH-OPTIONS] [-- TIGHTEN-OPTIONS...]" >&2
  exit 2
fi
manifest=$1 out=$2
shift 2
if [ -z "${SLURM_ARRAY_TASK_ID:-}" ] || [ -z "${SLURM_ARRAY_TASK_COUNT:-}" ]; then
  echo "slurm_batch.sh: not a task of a job array (no SLURM_ARRAY_TASK_ID/COUNT): sbatch --array=0-K" >&2
  exit 2
fi
job=$((SLURM_ARRAY_TASK_ID - ${SLURM_ARRAY_TASK_MIN:-0}))
# the one device SLURM gives the task: with --gres=gpu the GPU it exposes (the OpenCL driver
# sees only that one), else whatever TIGHTROPE_DEVICE or the manifest names
echo "task $SLURM_ARRAY_TASK_ID: job $job of $SLURM_ARRAY_TASK_COUNT on $(hostname)" >&2
exec "${TIGHTROPE:-tightrope}" batch "$manifest" -o "$out" --job "$job" --jobs "$SLURM_ARRAY_TASK_COUNT" "$@"
