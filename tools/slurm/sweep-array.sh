#!/bin/sh
# A sharded run as a SLURM job array and a merge job after it, for any
# program with --shard K/N and --merge (docs/platform.md "Sweeps on a SLURM
# cluster"); fp24-sweep.sh and mc1-sweep.sh are it with their sbatch files.
#   tools/slurm/sweep-array.sh NAME SHARD.sbatch MERGE.sbatch [--wait] [--cpus C] N OUTDIR PROGRAM [ARGS...]
# N shards of `PROGRAM ARGS`, C cpus (threads) each; reports in OUTDIR (a
# directory every node sees). Submits arrays of at most MAX_ARRAY tasks
# (environment, default 1000: SLURM's MaxArraySize is 1001) of
#   SHARD.sbatch OUTDIR PROGRAM N OFFSET ARGS...
# and `MERGE.sbatch OUTDIR PROGRAM N` with --dependency=afterok on all of
# them, which writes OUTDIR/merged.json. Prints the merge job's id; --wait
# waits for it and exits with its status (1 also when a shard failed and
# the merge never ran). Exit 2 on a usage error. NAME names the messages.
set -eu
[ $# -ge 3 ] || { echo "usage: sweep-array.sh NAME SHARD.sbatch MERGE.sbatch [--wait] [--cpus C] N OUTDIR PROGRAM [ARGS...]" >&2; exit 2; }
name=$1 shard_job=$2 merge_job=$3
shift 3
usage() { echo "usage: $name [--wait] [--cpus C] N OUTDIR PROGRAM [ARGS...]" >&2; exit 2; }
wait_flag="" cpus=1
while [ $# -gt 0 ]; do
  case $1 in
    --wait) wait_flag=--wait; shift ;;
    --cpus) [ $# -ge 2 ] || usage; cpus=$2; shift 2 ;;
    *) break ;;
  esac
done
[ $# -ge 3 ] || usage
n=$1 out=$2 program=$3
shift 3
case $n in ''|*[!0-9]*|0) echo "$name: N '$n' is not a positive integer" >&2; exit 2 ;; esac
case $cpus in ''|*[!0-9]*|0) echo "$name: --cpus '$cpus' is not a positive integer" >&2; exit 2 ;; esac
[ -x "$program" ] || { echo "$name: $program: not an executable" >&2; exit 2; }
mkdir -p "$out"
out=$(cd "$out" && pwd)
rm -f "$out/merged.json"  # a report of an earlier run must not pass for this one
max=${MAX_ARRAY:-1000}
deps="" offset=0
while [ "$offset" -lt "$n" ]; do
  m=$((n - offset)); [ "$m" -le "$max" ] || m=$max
  job=$(sbatch --parsable --array=1-"$m" --cpus-per-task="$cpus" "$shard_job" "$out" "$program" "$n" "$offset" "$@")
  deps="$deps:${job%%;*}"
  offset=$((offset + m))
done
# --kill-on-invalid-dep: a failed shard cancels the merge instead of leaving
# it pending for ever (and --wait returns, with status 0: hence the check of
# the merged report, removed before).
rc=0
sbatch --parsable $wait_flag --kill-on-invalid-dep=yes --dependency=afterok"$deps" \
  "$merge_job" "$out" "$program" "$n" || rc=$?
[ -n "$wait_flag" ] || exit "$rc"
if [ ! -s "$out/merged.json" ]; then
  echo "$name: no merged report: a shard failed (its log: $out/shard-K.log)" >&2
  [ "$rc" -ne 0 ] || rc=1
fi
exit "$rc"
