#!/bin/sh
# The golden frames (docs/renderer.md "Golden frames"): every standard scene
# at 96x64 on 1 and 16 NCs, the self-test frame and the RTL engine's frames,
# made by this build's mc1 and compared bit for bit (PNG SHA-256, every
# simulated time and count of the statistics) with tests/golden/. A refactor
# changes neither a pixel nor a simulated picosecond; a change that does on
# purpose rewrites the goldens with tools/bless-frames.sh. The same tests run
# in the default suite (ctest -L golden).
#   tools/frame-check.sh [BUILD_DIR]        (default build/)
set -eu
here=$(cd "$(dirname "$0")/.." && pwd)
build=$(cd "${1:-$here/build}" && pwd)
cmake --build "$build" --target mc1
cd "$build" && exec ctest -L golden --output-on-failure -j "$(nproc)"
