#!/bin/sh
# A sharded fp24-regress run as a SLURM job array and a merge job after it
# (docs/platform.md "Sweeps on a SLURM cluster").
#   tools/slurm/fp24-sweep.sh [OPTIONS] N OUTDIR FP24_REGRESS [ARGS...]
# N shards of `FP24_REGRESS ARGS`; reports in OUTDIR (a directory every node
# sees, as FP24_REGRESS must be): shard-K.json/.txt/.log, SLURM's
# shard-K.slurm.log, merged.json/.txt, merge.log, merge.slurm.log. OPTIONS
# (--wait, --cpus C: threads per shard, --partition P, --time T, --account A,
# --mem M, --qos Q, --sbatch OPT; and sbatch's SBATCH_* environment
# variables): sweep-array.sh.
# Prints the merge job's id; --wait waits for it and exits with its status
# (0 pass, 1 mismatch, 2 bad or missing shard report; 1 also when a shard
# failed and the merge never ran). Exit 2 on a usage error. The array and
# its merge: sweep-array.sh.
here=$(cd "$(dirname "$0")" && pwd)
exec "$here/sweep-array.sh" fp24-sweep.sh "$here/fp24-shard.sbatch" "$here/fp24-merge.sbatch" "$@"
