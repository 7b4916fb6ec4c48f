#!/usr/bin/env bash
# The scheduler wiring of tools/suite/ run here in local processes: each file must only turn the
# scheduler's index into --fraction, so the merged shards must hold every case once, with the statuses
# of a single run. Usage: scheduler_test.sh CASE TESSERA SOURCE_DIR WORK_DIR
set -euo pipefail
case_name=$1 tessera=$2 src=$3 work=$4/$1
rm -rf "$work" && mkdir -p "$work"
# A passing case removes its work directory; a failing one keeps it (tests/cli/cli_test.sh).
trap 'rc=$?; cd /; if [ $rc = 0 ]; then rm -rf "$work"; else echo "kept for inspection: $work" >&2; fi' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

# Five cases of the test-only subcommand (a few ms each), one of which fails: shard results differ.
cat > "$work/s.json" << 'JSON'
{"schema": 1, "name": "sched", "cases": [
  {"name": "a", "kind": "command", "steps": [["suite", "_case", "--mode", "pass"]]},
  {"name": "b", "kind": "command", "steps": [["suite", "_case", "--mode", "pass"]]},
  {"name": "c", "kind": "command", "steps": [["suite", "_case", "--mode", "fail"]]},
  {"name": "d", "kind": "command", "steps": [["suite", "_case", "--mode", "pass"]]},
  {"name": "e", "kind": "command", "steps": [["suite", "_case", "--mode", "pass"]]}]}
JSON

# merged results: "name status" per case, in suite order.
statuses() {
  python3 -c 'import json, sys; print(" ".join(c["name"] + ":" + c["status"] for c in json.load(open(sys.argv[1]))["cases"]))' "$1"
}
expected="a:pass b:pass c:fail d:pass e:pass"

case $case_name in
  slurm_array_runs_every_fraction_and_merges)
    # No sbatch here: SLURM_LOCAL=1 runs the array tasks with SLURM_ARRAY_TASK_ID = 1..3, then the merge.
    set +e
    SLURM_LOCAL=1 TESSERA=$tessera bash "$src/tools/suite/slurm-array.sh" "$work/s.json" 3 "$work/out" --quiet > "$work/log" 2>&1
    rc=$?
    set -e
    [[ $rc == 1 ]] || { cat "$work/log"; fail "the merge of a run with a failing case exits $rc, not 1"; }
    for k in 1 2 3; do
      [[ $(python3 -c 'import json, sys; print(json.load(open(sys.argv[1]))["run"]["fraction"])' "$work/out/shard-$k/results.json") == "$k/3" ]] ||
        fail "shard-$k did not run fraction $k/3"
    done
    got=$(statuses "$work/out/merged/results.json")
    [[ $got == "$expected" ]] || fail "merged: $got"
    ;;
  k8s_indexed_job_wires_the_completion_index)
    # The Job's own shell commands (read from the YAML), with JOB_COMPLETION_INDEX = 0..3 as Kubernetes
    # sets it, the image's paths mapped to this machine, and the merge's wait cut to 0 s.
    python3 -c 'import yaml' 2> /dev/null || { echo "SKIP: no python3 yaml"; exit 0; }
    python3 - "$src/tools/suite/k8s-indexed-job.yaml" "$work" << 'PY'
import sys, yaml
docs = list(yaml.safe_load_all(open(sys.argv[1])))
shard, merge = docs
assert shard["spec"]["completionMode"] == "Indexed"
n = shard["spec"]["completions"]
assert shard["spec"]["parallelism"] == n
for d in docs:
    env = {e["name"]: e["value"] for e in d["spec"]["template"]["spec"]["containers"][0]["env"]}
    assert env["SHARDS"] == str(n), (d["metadata"]["name"], env["SHARDS"], n)
open(sys.argv[2] + "/shard.sh", "w").write(shard["spec"]["template"]["spec"]["containers"][0]["args"][0])
open(sys.argv[2] + "/merge.sh", "w").write(merge["spec"]["template"]["spec"]["containers"][0]["args"][0])
open(sys.argv[2] + "/n", "w").write(str(n))
PY
    n=$(cat "$work/n")
    for f in shard merge; do
      sed -i "s#/opt/tessera/build/tessera#$tessera#g; s#\"/results/#\"$work/results/#g; s# /results/# $work/results/#g" "$work/$f.sh"
    done
    for ((i = 0; i < n; i++)); do
      JOB_COMPLETION_INDEX=$i SHARDS=$n SUITE=$work/s.json sh "$work/shard.sh" > /dev/null 2>&1 || fail "pod $i failed"
    done
    set +e
    SHARDS=$n MERGE_WAIT_SECONDS=0 sh "$work/merge.sh" > "$work/merge.log" 2>&1
    rc=$?
    set -e
    [[ $rc == 1 ]] || { cat "$work/merge.log"; fail "merge exits $rc, not 1"; }
    got=$(statuses "$work/results/merged/results.json")
    [[ $got == "$expected" ]] || fail "merged: $got"
    ;;
  *) fail "unknown case $case_name" ;;
esac
echo "PASS: $case_name"
