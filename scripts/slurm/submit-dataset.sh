#!/usr/bin/env bash
# Submits a dataset render to Slurm: a job array with one task per shard, then a merge job
# that runs only if every task succeeded (docs/datasets.md, "On a cluster: Slurm").
#
# Usage: scripts/slurm/submit-dataset.sh SPEC OUT N [extra sbatch args...]
#   Task I of the array (1..N) runs `skyrender dataset SPEC --out OUT --shard I/N`; the merge
#   job (--dependency=afterok:ARRAY --kill-on-invalid-dep=yes) runs `skyrender merge OUT`.
#   The extra arguments (--partition, --account, --time, --gres, ...) go to both sbatch calls.
#   Job logs go to OUT/slurm-logs/. Prints `array=ID merge=ID` on stdout.
#   Resubmitting the same command after a failed or cancelled task is safe: each task skips
#   the samples already in its shard's manifest.
# Environment:
#   SKYRENDER  the skyrender to run (default: `skyrender` on PATH); resolved to an absolute
#              path now, so the jobs run the same binary whatever their PATH. It, SPEC and OUT
#              must be on a disk that every node sees.
set -euo pipefail

die() { echo "error: submit-dataset.sh: $*" >&2; exit 1; }

[ $# -ge 3 ] || die "usage: submit-dataset.sh SPEC OUT N [extra sbatch args...]"
spec=$1 out=$2 n=$3
shift 3

{ [ -f "$spec" ] && [ -r "$spec" ]; } || die "spec '$spec' is not a readable file"
[[ "$n" =~ ^[1-9][0-9]*$ ]] || die "N must be a positive integer, got '$n'"
[ -n "$out" ] || die "OUT is empty"
command -v sbatch >/dev/null || die "sbatch not found; is Slurm's client installed and on PATH?"

sky=${SKYRENDER:-skyrender}
if [[ "$sky" != */* ]]; then
  sky_path=$(command -v -- "$sky" 2>/dev/null) || die "'$sky' not found on PATH; set SKYRENDER=/path/to/skyrender"
  sky=$sky_path
fi
{ [ -f "$sky" ] && [ -x "$sky" ]; } || die "SKYRENDER '$sky' is not an executable file"
sky=$(realpath -- "$sky")
spec=$(realpath -- "$spec")
mkdir -p -- "$out/slurm-logs" || die "cannot create '$out/slurm-logs'"
out=$(realpath -- "$out")
logs="$out/slurm-logs"

# Quotes a word for the job's /bin/sh (which need not be bash).
sq() { printf "'%s'" "$(printf %s "$1" | sed "s/'/'\\\\''/g")"; }

# --parsable prints "ID" or "ID;CLUSTER".
array_out=$(sbatch --parsable --array="1-$n" --job-name=skyrender-dataset --chdir="$out" \
  --output="$logs/dataset-%A_%a.out" "$@" \
  --wrap "exec $(sq "$sky") dataset $(sq "$spec") --out $(sq "$out") --shard \"\$SLURM_ARRAY_TASK_ID/$n\"") ||
  die "sbatch refused the job array (see its message above)"
array_id=${array_out%%;*}
[[ "$array_id" =~ ^[0-9]+$ ]] || die "sbatch printed '$array_out', not a job id"

if ! merge_out=$(sbatch --parsable --dependency="afterok:$array_id" --kill-on-invalid-dep=yes \
  --job-name=skyrender-merge --chdir="$out" --output="$logs/merge-%j.out" "$@" \
  --wrap "exec $(sq "$sky") merge $(sq "$out")"); then
  scancel "$array_id" 2>/dev/null || true
  die "sbatch refused the merge job; cancelled the array $array_id"
fi
merge_id=${merge_out%%;*}
[[ "$merge_id" =~ ^[0-9]+$ ]] || die "sbatch printed '$merge_out', not a job id"

echo "array=$array_id merge=$merge_id"
