#!/bin/sh
# Issue 39's benchmark: host time and memory of `mc1 render` against the
# object count, N one-triangle objects against the same N triangles in one
# object (the frames are the same PNG). Generates its scenes (a grid of N
# triangles in z = 0, one light) in a temporary directory; renders at 64x48
# on 4 NCs. Prints N, CPU seconds (user + system) and max RSS for both, and
# the ratios many / one.
#   tools/bench-objects.sh [--mc1 PATH] [N ...]     (default N: 250 1000 4000 16000 65535)
set -eu
usage() {
  sed -n '2,8p' "$0" | sed 's/^# \{0,1\}//'
}
here=$(cd "$(dirname "$0")/.." && pwd)
mc1=$here/build/bin/mc1
while [ $# -gt 0 ]; do
  case $1 in
    -h|--help) usage; exit 0 ;;
    --mc1) mc1=$2; shift 2 ;;
    --) shift; break ;;
    -*) echo "bench-objects.sh: unknown option $1 (see --help)" >&2; exit 2 ;;
    *) break ;;
  esac
done
[ $# -gt 0 ] || set -- 250 1000 4000 16000 65535
[ -x "$mc1" ] || { echo "bench-objects.sh: no mc1 at $mc1 (build it, or --mc1 PATH)" >&2; exit 1; }
[ -x /usr/bin/time ] || { echo "bench-objects.sh: needs /usr/bin/time (GNU time)" >&2; exit 1; }
tmp=$(mktemp -d "${TMPDIR:-/tmp}/bench-objects.XXXXXX")
trap 'rm -rf "$tmp"' EXIT INT TERM

# gen N many|one FILE: the scene as JSON.
gen() {
  awk -v n="$1" -v mode="$2" 'BEGIN {
    k = int(sqrt(n)); if (k * k < n) k++; s = 8.0 / k
    printf "{\"camera\": {\"eye\": [0, 0, 10], \"look_at\": [0, 0, 0], \"up\": [0, 1, 0], \"fov\": 60, \"width\": 64, \"height\": 48},\n"
    printf " \"lights\": [{\"position\": [0, 5, 10], \"intensity\": [1, 1, 1]}],\n"
    printf " \"materials\": [{\"name\": \"m\", \"colour\": [0.8, 0.6, 0.4], \"ko\": 0.1, \"kd\": 0.8}],\n \"objects\": [\n"
    if (mode == "one") printf "  {\"name\": \"all\", \"kind\": \"surface\", \"material\": \"m\", \"primitives\": [\n"
    for (i = 0; i < n; i++) {
      x = -4 + (i % k) * s; y = -4 + int(i / k) * s
      t = sprintf("{\"type\": \"triangle\", \"vertices\": [[%.17g, %.17g, 0], [%.17g, %.17g, 0], [%.17g, %.17g, 0]]}", x, y, x + s * 0.9, y, x, y + s * 0.9)
      sep = (i + 1 < n) ? ",\n" : "\n"
      if (mode == "one") printf "   %s%s", t, sep
      else printf "  {\"name\": \"o%d\", \"kind\": \"surface\", \"material\": \"m\", \"primitives\": [%s]}%s", i, t, sep
    }
    if (mode == "one") printf "  ]}\n"
    printf " ]}\n"
  }' > "$3"
}

# run FILE PNG: prints "cpu_seconds max_rss_kb"
run() {
  /usr/bin/time -f '%U %S %M' -o "$tmp/time" "$mc1" render "$1" --size 64x48 --nodes 4 --quiet --out "$2" >/dev/null
  awk '{ printf "%.2f %d\n", $1 + $2, $3 }' "$tmp/time"
}

printf '%6s  %10s %10s  %10s %10s  %7s %7s  %s\n' N many_cpu_s many_rss_MB one_cpu_s one_rss_MB cpu_x rss_x png
for n in "$@"; do
  gen "$n" many "$tmp/many.json"
  gen "$n" one "$tmp/one.json"
  set -- $(run "$tmp/many.json" "$tmp/many.png") $(run "$tmp/one.json" "$tmp/one.png")
  if cmp -s "$tmp/many.png" "$tmp/one.png"; then same=same; else same=DIFFERENT; fi
  awk -v n="$n" -v mc="$1" -v mr="$2" -v oc="$3" -v or="$4" -v same="$same" 'BEGIN {
    printf "%6d  %10.2f %10.1f  %10.2f %10.1f  %7.2f %7.2f  %s\n", n, mc, mr / 1024, oc, or / 1024, (oc > 0 ? mc / oc : 0), mr / or, same }'
done
