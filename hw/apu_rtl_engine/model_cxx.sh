#!/bin/sh
# The compiler launcher of the untraced verilated APU models (hw/apu_rtl_engine/CMakeLists.txt,
# apu_rtl_fast_models): CMake runs
#   model_cxx.sh CXX [LAUNCHER...] -- BUILD_CXX ARGS...
# and this runs [LAUNCHER...] CXX ARGS: the same compile line with CXX (clang++)
# in the place of the build's compiler, behind the build's launcher (ccache).
set -eu
cxx=$1
shift
launcher=""
while [ "$#" -gt 0 ] && [ "$1" != "--" ]; do
  launcher="$launcher $1"
  shift
done
shift 2  # "--" and the build's compiler
# shellcheck disable=SC2086  # the launcher's words
exec $launcher "$cxx" "$@"
