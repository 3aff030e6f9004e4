#!/bin/sh
# A sharded fp24-regress run as a SLURM job array and a merge job after it
# (docs/platform.md "Sweeps on a SLURM cluster").
#   tools/slurm/fp24-sweep.sh [--wait] [--cpus C] N OUTDIR FP24_REGRESS [ARGS...]
# N shards of `FP24_REGRESS ARGS`, C cpus (threads) each; reports in OUTDIR
# (a directory every node sees). Submits arrays of at most MAX_ARRAY tasks
# (environment, default 1000: SLURM's MaxArraySize is 1001) and the merge
# with --dependency=afterok on all of them. Prints the merge job's id;
# --wait waits for it and exits with its status (0 pass, 1 mismatch, 2 bad
# or missing shard report; 1 also when a shard failed and the merge never
# ran). Exit 2 on a usage error.
set -eu
here=$(cd "$(dirname "$0")" && pwd)
usage() { echo "usage: fp24-sweep.sh [--wait] [--cpus C] N OUTDIR FP24_REGRESS [ARGS...]" >&2; exit 2; }
wait_flag="" cpus=1
while [ $# -gt 0 ]; do
  case $1 in
    --wait) wait_flag=--wait; shift ;;
    --cpus) [ $# -ge 2 ] || usage; cpus=$2; shift 2 ;;
    *) break ;;
  esac
done
[ $# -ge 3 ] || usage
n=$1 out=$2 regress=$3
shift 3
case $n in ''|*[!0-9]*|0) echo "fp24-sweep.sh: N '$n' is not a positive integer" >&2; exit 2 ;; esac
case $cpus in ''|*[!0-9]*|0) echo "fp24-sweep.sh: --cpus '$cpus' is not a positive integer" >&2; exit 2 ;; esac
[ -x "$regress" ] || { echo "fp24-sweep.sh: $regress: not an executable" >&2; exit 2; }
mkdir -p "$out"
out=$(cd "$out" && pwd)
rm -f "$out/merged.json"  # a report of an earlier run must not pass for this one
max=${MAX_ARRAY:-1000}
deps="" offset=0
while [ "$offset" -lt "$n" ]; do
  m=$((n - offset)); [ "$m" -le "$max" ] || m=$max
  job=$(sbatch --parsable --array=1-"$m" --cpus-per-task="$cpus" \
        "$here/fp24-shard.sbatch" "$out" "$regress" "$n" "$offset" "$@")
  deps="$deps:${job%%;*}"
  offset=$((offset + m))
done
# --kill-on-invalid-dep: a failed shard cancels the merge instead of leaving
# it pending for ever (and --wait returns, with status 0: hence the check of
# the merged report, removed before).
rc=0
sbatch --parsable $wait_flag --kill-on-invalid-dep=yes --dependency=afterok"$deps" \
  "$here/fp24-merge.sbatch" "$out" "$regress" "$n" || rc=$?
[ -n "$wait_flag" ] || exit "$rc"
if [ ! -s "$out/merged.json" ]; then
  echo "fp24-sweep.sh: no merged report: a shard failed (its log: $out/shard-K.log)" >&2
  [ "$rc" -ne 0 ] || rc=1
fi
exit "$rc"
