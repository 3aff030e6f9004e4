#!/bin/sh
# Sets up, builds and runs the main job: the FP24 regression with its report.
set -eu
cd "$(dirname "$0")/.."
tools/build.sh
mkdir -p build/reports
build/bin/fp24-regress --json build/reports/fp24-regress.json --text build/reports/fp24-regress.txt "$@"
