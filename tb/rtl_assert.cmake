# CTest check (docs/apu-rtl.md "Assertions"): a broken rule fails under
# Icarus Verilog with its name and cycle. tb/rtl_assert_tb.sv runs apu_core
# on a small program, once as it is (no assertion may fire) and once per
# planted violation (the bench breaks the rule at APU cycle 6): the output
# must carry "APU_ASSERT <Rule> failed in ..." at that cycle's rising edge
# (time 10 * 6 + 25 = 85) and the bench's "cycle 6 pc 0x...".
#   cmake -DIVERILOG=... -DVVP=... -DAPUASM=... -DSOURCE_DIR=<project>
#         -DGENERATED=<build>/generated -DWORK=<dir> -P rtl_assert.cmake
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
set(rtl ${SOURCE_DIR}/apu_rtl)
file(GLOB packages ${rtl}/*_pkg.sv)
file(GLOB modules ${rtl}/*.sv)
list(REMOVE_ITEM modules ${packages})
set(vvp_file ${WORK}/rtl_assert.vvp)
execute_process(COMMAND ${IVERILOG} -g2012 -I${GENERATED} -I${rtl} -s rtl_assert_tb -o ${vvp_file}
                        ${GENERATED}/apu_pkg.sv ${packages} ${SOURCE_DIR}/tb/rtl_assert_tb.sv ${modules}
  RESULT_VARIABLE rc ERROR_VARIABLE err OUTPUT_VARIABLE out)
if(NOT rc EQUAL 0 OR err MATCHES "error")
  message(FATAL_ERROR "iverilog -g2012 failed (exit ${rc}):\n${out}${err}")
endif()

# MUL, ADD, CALL/RET, DBNZ: every unit but the function unit, the call stack.
file(WRITE ${WORK}/prog.apu "  li a1, 3\nloop:\n  lif f1, 1.5\n  mul f2, f1, f1\n  add f3, f2, f1\n"
                            "  call leaf\n  dbnz a1, loop\n  halt\nleaf:\n  ret\n")
execute_process(COMMAND ${APUASM} -o ${WORK}/prog.bin -x ${WORK}/prog.hex ${WORK}/prog.apu
  RESULT_VARIABLE rc ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "apuasm prog.apu: exit ${rc}\n${err}")
endif()

function(run_bench out_var)
  execute_process(COMMAND ${VVP} -n ${vvp_file} +program=${WORK}/prog.hex ${ARGN}
    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "vvp rtl_assert_tb ${ARGN}: exit ${rc}\n${out}${err}")
  endif()
  set(${out_var} "${out}${err}" PARENT_SCOPE)
endfunction()

run_bench(clean)
if(clean MATCHES "ERROR|FATAL" OR NOT clean MATCHES "run state 2")
  message(FATAL_ERROR "rtl_assert_tb without a planted violation: an assertion fired or the program did not halt:\n${clean}")
endif()
message(STATUS "rtl_assert_icarus: the program halts, no assertion fires")

foreach(rule RegfileZeroRegIsZero MulStageValids CallStackDepthLegal)
  run_bench(out +plant=${rule})
  if(NOT out MATCHES "rtl_assert_tb: cycle 6 pc 0x[0-9a-f]+: breaking ${rule}")
    message(FATAL_ERROR "+plant=${rule}: the bench did not break the rule at cycle 6:\n${out}")
  endif()
  if(NOT out MATCHES "ERROR: [^\n]*: APU_ASSERT ${rule} failed in rtl_assert_tb\\.dut[^\n]*\n[ \t]*Time: 85 ")
    message(FATAL_ERROR "+plant=${rule}: no \"APU_ASSERT ${rule} failed\" at cycle 6 (time 85):\n${out}")
  endif()
  string(REGEX MATCH "cycle 6 pc 0x[0-9a-f]+" where "${out}")
  message(STATUS "rtl_assert_icarus: ${rule} broken at ${where}: the assertion fires at its rising edge")
endforeach()
