#!/bin/sh
# Renders every standard scene at 96x64 on 1 and 16 NCs (and the self-test
# frame) with one mc1 binary, writing into OUTDIR the PNG bytes and the stats
# JSON without its host-time figures. Two runs (a binary from before a
# refactor, one after) are compared with `diff -r`: a refactor changes neither
# a pixel nor a simulated picosecond.
#   tools/frame-check.sh OUTDIR [MC1]        (MC1 defaults to build/bin/mc1)
set -eu
out=$1
mc1=${2:-build/bin/mc1}
here=$(cd "$(dirname "$0")/.." && pwd)
mkdir -p "$out"
for scene in "$here"/scenes/*.json; do
  name=$(basename "$scene" .json)
  for n in 1 16; do
    "$mc1" render "$scene" --size 96x64 --nodes "$n" --quiet \
      --out "$out/$name-$n.png" --stats "$out/$name-$n.json" --gantt "$out/$name-$n.svg"
    grep -v -i -e host -e "\"scene\"" "$out/$name-$n.json" > "$out/$name-$n.sim.json" && rm "$out/$name-$n.json"
  done
done
"$mc1" diag --nodes 16 --stats "$out/diag-16.json" >/dev/null
grep -v -i 'host' "$out/diag-16.json" > "$out/diag-16.sim.json" && rm "$out/diag-16.json"
echo "frame-check: $(ls "$out" | wc -l) files in $out"
