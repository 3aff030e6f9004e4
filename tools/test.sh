#!/bin/sh
# Sets up, builds and runs the default test suite (long sweeps: tools/test.sh -L long).
set -eu
cd "$(dirname "$0")/.."
tools/build.sh
if [ "$#" -eq 0 ]; then set -- -LE long; fi
cd build && ctest --output-on-failure -j "$(nproc)" "$@"
