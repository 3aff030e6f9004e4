#!/bin/sh
# The `cluster` CTest label (not in the default run): a single-node SLURM on
# localhost (tools/slurm/local-cluster.sh: munge key, slurm.conf, slurmctld
# and slurmd in a temporary directory), a 4-shard fp24-regress sweep as a job
# array with its merge job after it (tools/slurm/fp24-sweep.sh --wait), the
# merged report compared with the unsharded run's; a sweep whose shards fail
# exits non-zero with no merged report, the failing task's words in SLURM's
# log of it (shard-K.slurm.log); then a 3-shard `mc1 sweep` of a 16-point
# grid over a 2-frame camera orbit (tools/slurm/mc1-sweep.sh --wait, with
# site options passed to sbatch), its merged report checked against the
# unsharded run's, its table and plots written, SLURM's log of every task
# kept; the daemons stopped.
#   tests/cluster_test.sh FP24_REGRESS SOURCE_DIR MC1
set -eu
regress=$1 src=$2 mc1=$3
# Exit 77 (CTest: skipped) where a local SLURM cannot run at all.
if [ "$(id -u)" -ne 0 ]; then echo "cluster_test: skipped: slurmd needs root" >&2; exit 77; fi
for p in munged mungekey slurmctld slurmd sbatch; do
  command -v "$p" >/dev/null || [ -x "/usr/sbin/$p" ] ||
    { echo "cluster_test: skipped: no $p (tools/setup.sh slurm-wlm munge)" >&2; exit 77; }
done
dir=$(mktemp -d /tmp/mc1-cluster.XXXXXX)
cleanup() { "$src/tools/slurm/local-cluster.sh" stop "$dir/slurm"; rm -rf "$dir"; }
trap cleanup EXIT
eval "$("$src/tools/slurm/local-cluster.sh" start "$dir/slurm")"
export SLURM_CONF

args="--ops float,neg,add,mul --no-structured --random 200000 --seed 7"
# shellcheck disable=SC2086
"$src/tools/slurm/fp24-sweep.sh" --wait 4 "$dir/out" "$regress" $args >"$dir/merge-job"
for k in 1 2 3 4; do
  [ -s "$dir/out/shard-$k.json" ] || { echo "cluster_test: shard $k wrote no report" >&2; exit 1; }
done
grep -q '"shard": "all/4"' "$dir/out/merged.json" || { echo "cluster_test: merged.json is not all/4" >&2; exit 1; }
# shellcheck disable=SC2086
nice "$regress" $args --threads 2 --json "$dir/whole.json" >/dev/null
cmake -DA="$dir/whole.json" -DB="$dir/out/merged.json" -P "$src/tb/fp24_report_compare.cmake"
cat "$dir/out/merged.txt"

# A shard that fails (a usage error: no report) cancels the merge, and the
# sweep says so.
if "$src/tools/slurm/fp24-sweep.sh" --wait 2 "$dir/bad" "$regress" --ops fma >/dev/null 2>"$dir/bad.err"; then
  echo "cluster_test: a sweep of failing shards exited 0" >&2; exit 1
fi
grep -q "no merged report: a shard failed" "$dir/bad.err" || { cat "$dir/bad.err" >&2; exit 1; }
grep -q "unknown op 'fma'" "$dir/bad/shard-1.log"
grep -q "fp24-shard: shard 1/2: fp24-regress exit 2" "$dir/bad/shard-1.slurm.log" ||
  { echo "cluster_test: SLURM's log of the failed task does not say why" >&2; exit 1; }

# mc1 sweep as a job array: 16 points in 3 shards, the merge equal to the
# whole run's but for host figures.
grid="--scene $src/scenes/tiny.json --size 32x32 --orbit 2 --nodes 1,4 --schedules lpt,static --blocks 8,16x8"
# shellcheck disable=SC2086
"$src/tools/slurm/mc1-sweep.sh" --wait --time 10 --sbatch --comment=mc1-cluster-test 3 "$dir/sweep" "$mc1" $grid >/dev/null
# shellcheck disable=SC2086
nice "$mc1" sweep $grid --threads 2 --quiet --out-dir "$dir" --json "$dir/sweep-whole.json"
"$mc1" sweep --merge "$dir/sweep-whole.json" --json "$dir/sweep-whole-merged.json" --quiet
sim() { grep -v -e '"shard"' -e wall_seconds -e '"threads"' "$1" | sed 's/, "host_seconds": [0-9.e+-]*//'; }
sim "$dir/sweep-whole-merged.json" >"$dir/a.sim"
sim "$dir/sweep/merged.json" >"$dir/b.sim"
cmp "$dir/a.sim" "$dir/b.sim" || { echo "cluster_test: mc1 sweep's merge differs from the whole run" >&2; exit 1; }
grep -q '"shard": "all/3"' "$dir/sweep/merged.json"
[ "$(ls "$dir/sweep/points" | grep -c '^point-.*\.json$')" -eq 16 ] ||
  { echo "cluster_test: mc1 sweep wrote $(ls "$dir/sweep/points" | wc -l) point files, not 16" >&2; exit 1; }
for f in shard-1.slurm.log shard-2.slurm.log shard-3.slurm.log merge.slurm.log merged.svg; do
  [ -e "$dir/sweep/$f" ] || { echo "cluster_test: mc1 sweep left no $f" >&2; exit 1; }
done
[ "$(grep -c "^[0-9]" "$dir/sweep/merged.csv")" -eq 16 ] || { echo "cluster_test: merged.csv has not 16 points" >&2; exit 1; }
grep -q "every frame equal across its points (16 points)" "$dir/sweep/merge.log"
# No scene named: refused (mc1's default is a path of the machine that built it).
if "$src/tools/slurm/mc1-sweep.sh" 2 "$dir/noscene" "$mc1" --nodes 1 2>"$dir/noscene.err"; then
  echo "cluster_test: mc1-sweep.sh without --scene was submitted" >&2; exit 1
fi
grep -q "name the scene with --scene" "$dir/noscene.err"
echo "cluster_test: mc1 sweep of 16 points in 3 shards merged, equal to the whole run; table, plots and SLURM logs kept"
