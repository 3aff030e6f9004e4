#!/bin/sh
# Open-flow synthesis of the APU RTL with Yosys 0.23 and nextpnr-ice40
# (docs/apu-rtl.md "Synthesis"): writes BUILD/reports/synth.txt and .json,
# figures only of netlists that passed their gate-level check
# (tools/netlist.py; docs/apu-rtl.md "Gate-level checks").
#   tools/synth.sh [BUILD]            full report (BUILD defaults to build/)
#   tools/synth.sh --quick [BUILD]    read + proc + check of every unit, 0 latches
#   further options: --units fp24_mul,fp24_add  --no-ice40  --check-form quick|full
#   --require-check  --ice40-units U,...  --rtl DIR --out DIR  (tools/synth.py)
set -eu
here=$(cd "$(dirname "$0")" && pwd)
opts=""
build=""
while [ "$#" -gt 0 ]; do
  case "$1" in
    --units|--ice40-units|--check-form|--rtl|--out) opts="$opts $1 $2"; shift ;;
    -*) opts="$opts $1" ;;
    *) build=$1 ;;
  esac
  shift
done
# shellcheck disable=SC2086  # opts holds separate words
exec python3 "$here/synth.py" $opts "${build:-$here/../build}"
