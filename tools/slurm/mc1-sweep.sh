#!/bin/sh
# A sharded `mc1 sweep` as a SLURM job array and a merge job after it
# (docs/platform.md "Sweeps on a SLURM cluster").
#   tools/slurm/mc1-sweep.sh [--wait] [--cpus C] N OUTDIR MC1 [SWEEP ARGS...]
# N shards of `MC1 sweep SWEEP ARGS`, C cpus (--threads) each; in OUTDIR (a
# directory every node sees): points/point-I.json (and .png with --png),
# shard-K.json/.log, merged.json. Prints the merge job's id; --wait waits
# for it and exits with its status (0 every frame complete and equal, 1 not
# or a shard failed, 2 a bad or missing shard report). The array and its
# merge: sweep-array.sh.
here=$(cd "$(dirname "$0")" && pwd)
exec "$here/sweep-array.sh" mc1-sweep.sh "$here/mc1-sweep-shard.sbatch" "$here/mc1-sweep-merge.sbatch" "$@"
