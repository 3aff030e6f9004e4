#!/bin/sh
# Sets up, builds and runs the main job: the FP24 regression with its report,
# then the machine renders the Whitted scene (build/reports/whitted*).
set -eu
cd "$(dirname "$0")/.."
tools/build.sh
mkdir -p build/reports
build/bin/fp24-regress --json build/reports/fp24-regress.json --text build/reports/fp24-regress.txt "$@"
# The machine renders the Whitted scene with the defaults (16 NCs, ISS, lpt,
# the scene's 320x240, blocks of 16): frame, statistics and Gantt chart.
build/bin/mc1 render scenes/whitted.json --out build/reports/whitted.png \
  --stats build/reports/whitted-stats.json --gantt build/reports/whitted-gantt.svg
