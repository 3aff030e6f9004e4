#!/bin/sh
# tools/slurm's shard tasks, run here without SLURM (SLURM_ARRAY_TASK_ID set
# by hand, as sbatch would): a task whose run fails leaves no report, even
# where an earlier run left one, so the merge cannot pass a stale grid
# (issue 39); a task that runs writes its report and exits 0.
#   slurm_shard_test.sh FP24_REGRESS MC1 SOURCE_DIR
set -u
regress=$1 mc1=$2 src=$3
dir=$(mktemp -d) || exit 1
trap 'rm -rf "$dir"' EXIT
fail() { echo "slurm_shard_test: $*" >&2; exit 1; }

# task(SCRIPT PROGRAM ARGS...): shard 1 of 1, as array task 1; its status.
task() {
  script=$1 program=$2
  shift 2
  SLURM_ARRAY_TASK_ID=1 sh "$src/tools/slurm/$script" "$dir" "$program" 1 0 "$@" 2>"$dir/task.err"
}

for stale in shard-1.json shard-1.txt; do echo '{"stale": true}' >"$dir/$stale"; done
task fp24-shard.sbatch "$regress" --ops fma && fail "fp24-shard: a failed run exited 0"
[ ! -e "$dir/shard-1.json" ] || fail "fp24-shard: the earlier run's shard-1.json is left for the merge"
grep -q "shard 1/1: fp24-regress exit 2" "$dir/task.err" || fail "fp24-shard: no message naming the shard: $(cat "$dir/task.err")"

task fp24-shard.sbatch "$regress" --ops float ||
  fail "fp24-shard: a passing shard failed: $(cat "$dir/task.err" "$dir/shard-1.log")"
grep -q '"passed": true' "$dir/shard-1.json" || fail "fp24-shard: no passing report"

echo '{"stale": true}' >"$dir/shard-1.json"
task mc1-sweep-shard.sbatch "$mc1" --no-such-option && fail "mc1-sweep-shard: a failed run exited 0"
[ ! -e "$dir/shard-1.json" ] || fail "mc1-sweep-shard: the earlier run's shard-1.json is left for the merge"
echo "slurm_shard_test: a failed shard leaves no report; a passing one writes it"
