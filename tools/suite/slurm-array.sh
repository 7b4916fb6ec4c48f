#!/usr/bin/env bash
# Runs a Tessera suite as a Slurm array job: task i of N runs `tessera suite run --fraction i/N`, and a
# merge job that depends on the whole array joins the shards (docs/suite.md).
#
#   tools/suite/slurm-array.sh SUITE.json SHARDS OUTDIR [extra `suite run` options...]
#
# OUTDIR must be on a file system that every node sees: shard i writes OUTDIR/shard-i/, the merge
# writes OUTDIR/merged/ (results.json, junit.xml, index.html). TESSERA names the executable (default:
# build/tessera of this clone); SBATCH_ARGS adds sbatch options (partition, account, time, ...).
# The array index is 1-based (--array=1-N) because --fraction's K is: SLURM_ARRAY_TASK_ID is K.
# The merge runs with afterany, not afterok: a shard with failing cases exits 1 but still wrote its
# results, and the merge is what reports them.
#
# Without Slurm (or with SLURM_LOCAL=1) the script runs the same task and merge commands here, one
# after the other, with SLURM_ARRAY_TASK_ID set as Slurm would set it: that is how it is tested.
set -euo pipefail
if [[ $# -lt 3 ]]; then
  echo "usage: $0 SUITE.json SHARDS OUTDIR [suite run options...]" >&2
  exit 2
fi
suite=$1 shards=$2 out=$3
shift 3
if ! [[ $shards =~ ^[1-9][0-9]*$ ]]; then
  echo "$0: SHARDS '$shards': expected a whole number >= 1" >&2
  exit 2
fi
here=$(cd "$(dirname "$0")/../.." && pwd)
tessera=${TESSERA:-$here/build/tessera}
mkdir -p "$out"
extra=$(printf ' %q' "$@")

# The two job scripts; %q-quoting keeps paths with spaces intact.
task_script="#!/usr/bin/env bash
set -u
$(printf '%q' "$tessera") suite run $(printf '%q' "$suite") --fraction \"\$SLURM_ARRAY_TASK_ID/$shards\" -o $(printf '%q' "$out")/shard-\$SLURM_ARRAY_TASK_ID$extra"
shard_dirs=$(for ((i = 1; i <= shards; i++)); do printf ' %q' "$out/shard-$i"; done)
merge_script="#!/usr/bin/env bash
set -u
$(printf '%q' "$tessera") suite merge$shard_dirs -o $(printf '%q' "$out")/merged"

if [[ ${SLURM_LOCAL:-0} != 1 ]] && command -v sbatch > /dev/null; then
  # shellcheck disable=SC2086
  array_id=$(sbatch --parsable ${SBATCH_ARGS:-} --job-name=tessera-suite --array="1-$shards" \
    --output="$out/slurm-%A_%a.log" --wrap="bash -c $(printf '%q' "$task_script")")
  # shellcheck disable=SC2086
  merge_id=$(sbatch --parsable ${SBATCH_ARGS:-} --job-name=tessera-suite-merge --dependency="afterany:${array_id%%;*}" \
    --output="$out/slurm-merge-%j.log" --wrap="bash -c $(printf '%q' "$merge_script")")
  echo "submitted array job $array_id ($shards tasks) and merge job $merge_id; results: $out/merged/index.html"
  exit 0
fi

echo "$0: no sbatch (or SLURM_LOCAL=1): running the $shards tasks and the merge here" >&2
for ((i = 1; i <= shards; i++)); do
  SLURM_ARRAY_TASK_ID=$i bash -c "$task_script" || true  # exit 1 = failing cases: the merge reports them
done
bash -c "$merge_script"
