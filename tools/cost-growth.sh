#!/bin/sh
# Cost growth of the co-simulation (docs/platform.md "Cost growth"): host
# time and peak memory (/usr/bin/time -v) of `mc1 render` against the node
# count and the frame size, and the simulated parallel efficiency.
#   tools/cost-growth.sh [--mc1 MC1] [--scene S] [--nodes LIST] [--sizes LIST]
#                        [--threads N] OUTDIR
# LIST: space- or comma-separated (defaults: nodes 1,4,16,64,256,1024, sizes
# 64,128,256,512,1024 for NxN frames). Each cell is one run; its line goes
# to OUTDIR/cells.csv as soon as it is done, and a cell already there is
# not run again, so a grid can be run in parts (a reduced grid first) and
# completed later. OUTDIR/table.md is rewritten from cells.csv after every
# cell: host seconds (wall and user), peak RSS, simulated frame time, the
# mean APU utilization, and the efficiency T(1 NC) / (N T(N NCs)) of each
# measured cell whose frame size also has the 1-NC cell. Runs niced.
set -eu
here=$(cd "$(dirname "$0")/.." && pwd)
mc1=$here/build/bin/mc1 scene=$here/scenes/whitted.json
nodes="1 4 16 64 256 1024" sizes="64 128 256 512 1024" threads=""
usage() { echo "usage: cost-growth.sh [--mc1 MC1] [--scene S] [--nodes LIST] [--sizes LIST] [--threads N] OUTDIR" >&2; exit 2; }
while [ $# -gt 1 ]; do
  case $1 in
    --mc1) mc1=$2; shift 2 ;;
    --scene) scene=$2; shift 2 ;;
    --nodes) nodes=$(echo "$2" | tr , ' '); shift 2 ;;
    --sizes) sizes=$(echo "$2" | tr , ' '); shift 2 ;;
    --threads) threads="--threads $2"; shift 2 ;;
    *) break ;;
  esac
done
[ $# -eq 1 ] || usage
out=$1
[ -x /usr/bin/time ] || { echo "cost-growth.sh: needs /usr/bin/time (Debian package time)" >&2; exit 2; }
mkdir -p "$out"
csv=$out/cells.csv
[ -s "$csv" ] || echo "nodes,size,wall_s,user_s,rss_kb,simulated_ps,apu_utilization,load" >"$csv"

table() {
  awk -F, -v nodes="$nodes" -v sizes="$sizes" '
    NR > 1 { k = $1 "," $2; wall[k] = $3; user[k] = $4; rss[k] = $5; sim[k] = $6; util[k] = $7; load[k] = $8 }
    function row(title, what,   n, s, i, j, k, line) {
      line = "| " title " |"; for (j = 1; j <= ns; ++j) line = line " " S[j] "x" S[j] " |"; print line
      line = "|---|"; for (j = 1; j <= ns; ++j) line = line "---:|"; print line
      for (i = 1; i <= nn; ++i) {
        line = "| " N[i] " |"
        for (j = 1; j <= ns; ++j) {
          k = N[i] "," S[j]
          if (!(k in wall)) { line = line " - |"; continue }
          if (what == "wall") line = line sprintf(" %.1f (%.1f) |", wall[k], user[k])
          else if (what == "rss") line = line sprintf(" %.0f |", rss[k] / 1024)
          else if (what == "sim") line = line sprintf(" %.3f |", sim[k] * 1e-12)
          else if (what == "eff") {
            b = "1," S[j]
            if (b in sim && sim[k] > 0) line = line sprintf(" %.1f %% (util %.1f %%) |", 100 * sim[b] / (N[i] * sim[k]), 100 * util[k])
            else line = line sprintf(" - (util %.1f %%) |", 100 * util[k])
          }
        }
        print line
      }
      print ""
    }
    END {
      nn = split(nodes, N, " "); ns = split(sizes, S, " ")
      print "Host seconds, wall (user), by NCs (rows) and frame size:"; print ""; row("NCs", "wall")
      print "Peak resident memory, MiB:"; print ""; row("NCs", "rss")
      print "Simulated frame time, s:"; print ""; row("NCs", "sim")
      print "Simulated parallel efficiency T1 / (N TN) (mean APU utilization):"; print ""; row("NCs", "eff")
    }' "$csv" >"$out/table.md"
}

for s in $sizes; do
  for n in $nodes; do
    if grep -q "^$n,$s," "$csv"; then continue; fi
    cell=$out/n$n-$s
    load=$(cut -d' ' -f1 /proc/loadavg)
    # shellcheck disable=SC2086
    if ! nice -n 10 /usr/bin/time -v -o "$cell.time" "$mc1" render "$scene" --size "${s}x$s" --nodes "$n" \
         $threads --quiet --stats "$cell.json" >"$cell.log" 2>&1; then
      echo "cost-growth.sh: $n NCs, ${s}x$s failed (see $cell.log)" >&2; exit 1
    fi
    wall=$(awk -F': ' '/Elapsed \(wall clock\)/ { n = split($2, t, ":"); s = 0; for (i = 1; i <= n; ++i) s = 60 * s + t[i]; print s }' "$cell.time")
    user=$(awk -F': ' '/User time/ { print $2 }' "$cell.time")
    rss=$(awk -F': ' '/Maximum resident set size/ { print $2 }' "$cell.time")
    sim=$(sed -n 's/^  "simulated_time_ps": \([0-9]*\),$/\1/p' "$cell.json")
    util=$(sed -n 's/.*"apu_utilization_mean": \([0-9.e-]*\).*/\1/p' "$cell.json")
    echo "$n,$s,$wall,$user,$rss,$sim,$util,$load" >>"$csv"
    echo "cost-growth: $n NCs ${s}x$s: wall ${wall}s user ${user}s rss ${rss}KB simulated ${sim}ps (load $load)"
    table
  done
done
table
cat "$out/table.md"
