#!/bin/sh
# A sharded `mc1 sweep` as a SLURM job array and a merge job after it
# (docs/platform.md "Sweeps on a SLURM cluster").
#   tools/slurm/mc1-sweep.sh [OPTIONS] N OUTDIR MC1 --scene FILE [SWEEP ARGS...]
# N shards of `MC1 sweep --scene FILE SWEEP ARGS`; in OUTDIR (a directory
# every node sees, as MC1, its libraries and the scene must be):
# points/point-I.json (and .png with --png), shard-K.json/.log, SLURM's own
# shard-K.slurm.log, and the merge's merged.json, merged.csv (the table),
# merged.svg (the plots), merge.log, merge.slurm.log. --scene is required:
# mc1's default scene is a path where mc1 was built or installed, which the
# nodes need not have. OPTIONS (--wait, --cpus C, --partition P, --time T,
# --account A, --mem M, --qos Q, --sbatch OPT; and sbatch's SBATCH_*
# environment variables): sweep-array.sh. Prints the merge job's id; --wait
# waits for it and exits with its status (0 every frame complete and equal,
# 1 not or a shard failed, 2 a bad or missing shard report).
here=$(cd "$(dirname "$0")" && pwd)
scene=no
for a in "$@"; do
  case $a in --scene|--scene=*) scene=yes ;; esac
done
if [ "$scene" = no ]; then
  echo "mc1-sweep.sh: name the scene with --scene FILE (on a path every node sees): mc1's default" \
    "scene is a path of the machine it was built or installed on" >&2
  exit 2
fi
exec "$here/sweep-array.sh" mc1-sweep.sh "$here/mc1-sweep-shard.sbatch" "$here/mc1-sweep-merge.sbatch" "$@"
