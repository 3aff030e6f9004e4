#!/bin/sh
# A sharded run as a SLURM job array and a merge job after it, for any
# program with --shard K/N and --merge (docs/platform.md "Sweeps on a SLURM
# cluster"); fp24-sweep.sh and mc1-sweep.sh are it with their sbatch files.
#   tools/slurm/sweep-array.sh NAME SHARD.sbatch MERGE.sbatch [OPTIONS] N OUTDIR PROGRAM [ARGS...]
# N shards of `PROGRAM ARGS`; reports in OUTDIR (a directory every node
# sees, as PROGRAM and the files ARGS name must be). OPTIONS:
#   --wait            wait for the merge job; exit with its status
#   --cpus C          C cpus (threads) per shard (default 1)
#   --partition P, --time T, --account A, --mem M, --qos Q
#                     passed to every sbatch as the same option
#   --sbatch OPT      any other sbatch option (one word, e.g. --sbatch
#                     --constraint=avx2); repeatable
# sbatch also reads its own SBATCH_* environment variables (SBATCH_PARTITION,
# SBATCH_TIMELIMIT, SBATCH_ACCOUNT, SBATCH_MEM_PER_NODE, ...): they reach
# every job too. Submits arrays of at most MAX_ARRAY tasks (environment,
# default 1000: SLURM's MaxArraySize is 1001) of
#   SHARD.sbatch OUTDIR PROGRAM N OFFSET ARGS...
# and `MERGE.sbatch OUTDIR PROGRAM N` with --dependency=afterok on all of
# them, which writes OUTDIR/merged.json. SLURM's own output of each task (a
# time-limit or memory kill, a missing program) is kept in
# OUTDIR/shard-K.slurm.log (OUTDIR/shard-OFFSET+I.slurm.log for the arrays
# after the first MAX_ARRAY shards) and OUTDIR/merge.slurm.log. Prints the
# merge job's id; --wait waits for it and exits with its status (1 also when
# a shard failed and the merge never ran). Exit 2 on a usage error. NAME
# names the messages.
set -euf  # -f: the site options below are split into words, never globbed
[ $# -ge 3 ] || { echo "usage: sweep-array.sh NAME SHARD.sbatch MERGE.sbatch [OPTIONS] N OUTDIR PROGRAM [ARGS...]" >&2; exit 2; }
name=$1 shard_job=$2 merge_job=$3
shift 3
usage() {
  echo "usage: $name [--wait] [--cpus C] [--partition P] [--time T] [--account A] [--mem M] [--qos Q]" \
    "[--sbatch OPT]... N OUTDIR PROGRAM [ARGS...]" >&2
  exit 2
}
wait_flag="" cpus=1 site=""
while [ $# -gt 0 ]; do
  case $1 in
    --wait) wait_flag=--wait; shift ;;
    --cpus) [ $# -ge 2 ] || usage; cpus=$2; shift 2 ;;
    --partition|--time|--account|--mem|--qos)
      [ $# -ge 2 ] && [ -n "$2" ] || usage
      case $2 in *[[:space:]]*) echo "$name: $1 '$2' has a space" >&2; exit 2 ;; esac
      site="$site $1=$2"; shift 2 ;;
    --sbatch)
      [ $# -ge 2 ] || usage
      case $2 in -*) ;; *) echo "$name: --sbatch '$2' is not an sbatch option" >&2; exit 2 ;; esac
      case $2 in *[[:space:]]*) echo "$name: --sbatch '$2' has a space: one word, --opt=value" >&2; exit 2 ;; esac
      site="$site $2"; shift 2 ;;
    -*) echo "$name: unknown option '$1'" >&2; usage ;;
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
  log="$out/shard-%a.slurm.log"
  [ "$offset" -eq 0 ] || log="$out/shard-$offset+%a.slurm.log"
  # shellcheck disable=SC2086 # $site: the site's options, one word each
  job=$(sbatch --parsable $site --array=1-"$m" --cpus-per-task="$cpus" --output="$log" \
    "$shard_job" "$out" "$program" "$n" "$offset" "$@")
  deps="$deps:${job%%;*}"
  offset=$((offset + m))
done
# --kill-on-invalid-dep: a failed shard cancels the merge instead of leaving
# it pending for ever (and --wait returns, with status 0: hence the check of
# the merged report, removed before).
rc=0
# shellcheck disable=SC2086
sbatch --parsable $site $wait_flag --kill-on-invalid-dep=yes --dependency=afterok"$deps" \
  --output="$out/merge.slurm.log" "$merge_job" "$out" "$program" "$n" || rc=$?
[ -n "$wait_flag" ] || exit "$rc"
if [ ! -s "$out/merged.json" ]; then
  echo "$name: no merged report: a shard failed (its logs: $out/shard-K.log, and SLURM's $out/shard-K.slurm.log)" >&2
  [ "$rc" -ne 0 ] || rc=1
fi
exit "$rc"
