# CTest check that the gate-level check catches a netlist bug
# (docs/apu-rtl.md "Gate-level checks"): a scratch copy of apu_rtl/ with
# fp24_classify.sv's all-ones constant written `'1` again, as before c8826d4
# (Debian's Yosys 0.23 reads it as 1: exponent 1 decoded as inf/NaN), must
# fail the multiplier's netlist check with its mismatches listed.
#   cmake -DPYTHON=... -DSOURCE_DIR=<project> -DBUILD=<build> -DWORK=<dir> -P netlist_planted_bug.cmake
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
file(COPY ${SOURCE_DIR}/apu_rtl/ DESTINATION ${WORK}/rtl FILES_MATCHING PATTERN "*.sv" PATTERN "*.svh")
set(f ${WORK}/rtl/fp24_classify.sv)
file(READ ${f} text)
string(REPLACE "EXP_ONES = {EXP_W{1'b1}};" "EXP_ONES = '1;" planted "${text}")
if(planted STREQUAL text)
  message(FATAL_ERROR "fp24_classify.sv has no `EXP_ONES = {EXP_W{1'b1}};` to plant the old '1 into: update this test")
endif()
file(WRITE ${f} "${planted}")
execute_process(COMMAND ${PYTHON} ${SOURCE_DIR}/tools/netlist.py check --units fp24_mul --form quick
                        --rtl ${WORK}/rtl --out ${WORK}/netlist ${BUILD}
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 1 OR NOT err MATCHES "fp24_mul netlist: [0-9]+ of [0-9]+ vectors differ from the model")
  message(FATAL_ERROR "the planted '1 was not caught (exit ${rc}, want 1 with the mismatches):\n${out}${err}")
endif()
string(REGEX MATCH "[0-9]+ of [0-9]+ vectors differ" caught "${err}")
string(REGEX MATCH "\\[known\\] mul [^\n]*" first "${err}")
message(STATUS "netlist_planted_bug: caught: ${caught}; first: ${first}")

# tools/synth.py refuses to report figures of that netlist: exit 1 naming
# the unit and its failed check, no report written.
execute_process(COMMAND ${PYTHON} ${SOURCE_DIR}/tools/synth.py --units fp24_mul --no-ice40
                        --rtl ${WORK}/rtl --out ${WORK}/netlist ${BUILD}
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 1 OR NOT err MATCHES "synth: FAILED: fp24_mul: netlist check failed, no figures of it reported"
   OR EXISTS ${WORK}/netlist/reports/synth.txt)
  message(FATAL_ERROR "tools/synth.py reported on the netlist that failed its check (exit ${rc}):\n${out}${err}")
endif()
message(STATUS "netlist_planted_bug: tools/synth.py refused: exit 1, no synth.txt")
