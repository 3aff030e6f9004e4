#!/bin/sh
# Installs the Debian packages the project needs, when they are missing.
#   tools/setup.sh [EXTRA-PACKAGE...]   (gtkwave: the waveform viewer, and fst2vcd
#   for the trace tests; clang: the untraced verilated APU models,
#   hw/apu_rtl_engine/CMakeLists.txt, and tools/test.sh --fuzz; the cluster
#   test needs slurm-wlm munge: tools/setup.sh slurm-wlm munge, docs/platform.md;
#   chromium: the SVG tests open the plots in headless Chromium; lcov: genhtml,
#   the HTML report of tools/test.sh --coverage)
set -eu
PKGS="build-essential cmake pkg-config libsystemc-dev verilator libglm-dev libgtest-dev libmpfr-dev libgmp-dev zlib1g-dev libpng-dev libcli11-dev python3 nlohmann-json3-dev python3-dev python3-numpy pybind11-dev yosys z3 iverilog nextpnr-ice40 clang gtkwave chromium lcov $*"
missing=""
for p in $PKGS; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing="$missing $p"
done
if [ -n "$missing" ]; then
  echo "setup: installing$missing"
  SUDO=""; [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq $missing
fi
