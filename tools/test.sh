#!/bin/sh
# Sets up, builds and runs the default test suite (long sweeps: tools/test.sh -L long).
#   tools/test.sh [CTEST-ARGS]   the Release build in build/ (default: -LE long)
#   tools/test.sh --asan         ASan + UBSan build in build-asan/, default suite, leaks checked
#   tools/test.sh --fuzz         libFuzzer harnesses (clang) in build-fuzz/, the fuzz label
#   tools/test.sh --cluster      the cluster label: a local single-node SLURM (root;
#                                installs slurm-wlm and munge; docs/platform.md)
#   tools/test.sh --coverage     code and functional coverage of the APU: a
#                                coverage build in build-cov/, the regressions
#                                that feed it, build-cov/reports/ (coverage.json,
#                                coverage.txt, coverage-html/), the goals checked
#                                (tools/coverage.py; docs/fp24-verification.md)
set -eu
cd "$(dirname "$0")/.."
if [ "${1:-}" = --coverage ]; then
  shift
  tools/setup.sh
  exec python3 tools/coverage.py run "$@"
fi
case "${1:-}" in
  --asan|--fuzz)
    preset=${1#--}
    if [ "$preset" = fuzz ]; then tools/setup.sh clang; else tools/setup.sh; fi
    cmake --preset "$preset" >/dev/null
    cmake --build --preset "$preset" -j "$(nproc)"
    exec ctest --preset "$preset" -j "$(nproc)"
    ;;
esac
if [ "${1:-}" = --cluster ]; then
  tools/setup.sh slurm-wlm munge
  shift
  set -- -L cluster "$@"
fi
tools/build.sh
if [ "$#" -eq 0 ]; then set -- -LE long; fi
cd build && ctest --output-on-failure -j "$(nproc)" "$@"
