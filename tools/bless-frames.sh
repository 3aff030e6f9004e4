#!/bin/sh
# Rewrites the golden frames (tests/golden/*.txt, docs/renderer.md "Golden
# frames") from this build's mc1: runs the golden tests themselves with
# MC1_BLESS_FRAMES=1, so each frame of tests/golden/frames.txt writes its
# golden instead of comparing; the frames that share another's golden (the
# RTL engine's) are still compared, and the goldens must still agree (one
# PNG per scene and size whatever the node count or engine): a frame that
# differs there is a bug, not a golden. Then shows what moved: commit it
# with the reason.
#   tools/bless-frames.sh [BUILD_DIR]        (default build/; or: cmake --build build --target bless-frames)
set -eu
here=$(cd "$(dirname "$0")/.." && pwd)
build=$(cd "${1:-$here/build}" && pwd)
[ -n "${MC1_FRAMES_BUILT:-}" ] || cmake --build "$build" --target mc1   # the bless-frames target has built it
(cd "$build" && MC1_BLESS_FRAMES=1 ctest -L golden --output-on-failure -j "$(nproc)")
cd "$here" && git status --short tests/golden && git diff --stat tests/golden
