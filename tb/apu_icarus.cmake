# CTest check (docs/apu-rtl.md "Second simulator"): apu_core, compiled
# unmodified with Icarus Verilog, runs kernel programs to the same end state
# and in the same number of cycles as the ISS and the verilated core.
#   cmake -DIVERILOG=... -DVVP=... -DAPUASM=... -DAPU_RUN=... -DSOURCE_DIR=<project>
#         -DGENERATED=<build>/generated -DWORK=<dir> -P apu_icarus.cmake
# 1. iverilog -g2012 of tb/apu_icarus_tb.sv and every apu_rtl/*.sv;
# 2. per program: apuasm -x, then tb/apu_icarus_tb.sv under vvp and apu-run
#    --engine iss and --engine rtl on the same data files: the cycle count,
#    CC, FLAGS, every F and A register and the data words read back must
#    agree.
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
set(rtl ${SOURCE_DIR}/apu_rtl)
file(GLOB packages ${rtl}/*_pkg.sv)
file(GLOB modules ${rtl}/*.sv)
list(REMOVE_ITEM modules ${packages})
set(vvp_file ${WORK}/apu_icarus.vvp)
execute_process(COMMAND ${IVERILOG} -g2012 -I${GENERATED} -s apu_icarus_tb -o ${vvp_file}
                        ${GENERATED}/apu_pkg.sv ${packages} ${SOURCE_DIR}/tb/apu_icarus_tb.sv ${modules}
  RESULT_VARIABLE rc ERROR_VARIABLE err OUTPUT_VARIABLE out)
if(NOT rc EQUAL 0 OR err MATCHES "error")
  message(FATAL_ERROR "iverilog -g2012 failed (exit ${rc}):\n${out}${err}")
endif()

# The data files: $readmemh text, which apu-run reads too.
# r_xform's camera batch (firmware/kernels/r_layout.inc): COUNT 1, XM_CAMERA,
# eye (0, 0, 5), look-at the origin, up (0, 1, 0), 60 degrees, 96x64, pi/360;
# then the end of the stream. It runs MUL, ADD, SUB, NEG, FLOAT, RECIP,
# SQRT, SIN and COS, LD/ST, CALL/RET and two SWAPDs.
file(WRITE ${WORK}/camera.hex "@0 000001 000000\n@b 414000 000000 000000\n"
           "@10 000000 000000 000000 000000 3f0000 000000 44e000 000060 000040 381df4\n")
file(WRITE ${WORK}/end.hex "@0 000000\n")
# xform4 (docs/apu-tools.md): one block of two vertices, a DBNZ loop.
file(WRITE ${WORK}/xform4.hex "@0 000002\n@10 400000 000000 000000 3f0000\n000000 400000 000000 400000\n"
           "000000 000000 400000 000000\n000000 000000 000000 3f0000\n"
           "@20 3f0000 400000 408000 3f0000\nbf0000 000000 3f0000 3f0000\n")

# run(name kernel read_addr read_count data...)
function(run name kernel read_addr read_count)
  set(hex ${WORK}/${name}.prog.hex)
  execute_process(COMMAND ${APUASM} -o ${WORK}/${name}.bin -x ${hex} ${SOURCE_DIR}/firmware/kernels/${kernel}
    RESULT_VARIABLE rc ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "apuasm ${kernel}: exit ${rc}\n${err}")
  endif()
  set(plus)
  set(opts)
  set(i 0)
  foreach(d IN LISTS ARGN)
    list(APPEND plus +data${i}=${WORK}/${d})
    list(APPEND opts --data ${WORK}/${d})
    math(EXPR i "${i} + 1")
  endforeach()
  math(EXPR read_dec "${read_addr}")
  execute_process(COMMAND ${VVP} -n ${vvp_file} +program=${hex} ${plus} +read_addr=${read_dec}
                          +read_count=${read_count}
    RESULT_VARIABLE rc OUTPUT_VARIABLE icarus ERROR_VARIABLE err)
  if(NOT rc EQUAL 0 OR icarus MATCHES "FATAL|ERROR" OR NOT icarus MATCHES "icarus: halted after")
    message(FATAL_ERROR "vvp apu_icarus_tb on ${kernel} failed (exit ${rc}):\n${icarus}${err}")
  endif()
  # Icarus's own notes ($readmemh of a short file) are not the state.
  string(REGEX REPLACE "WARNING:[^\n]*\n" "" icarus "${icarus}")
  string(REGEX MATCH "halted after ([0-9]+) cycles" _ "${icarus}")
  set(icarus_cycles ${CMAKE_MATCH_1})
  string(REGEX REPLACE "^[^\n]*\n" "" icarus_state "${icarus}")
  foreach(engine iss rtl)
    execute_process(COMMAND ${APU_RUN} ${WORK}/${name}.bin --engine ${engine} ${opts}
                            --read ${read_addr}:${read_count}
      RESULT_VARIABLE rc OUTPUT_VARIABLE want ERROR_VARIABLE err)
    if(NOT rc EQUAL 0)
      message(FATAL_ERROR "apu-run ${kernel} --engine ${engine}: exit ${rc}\n${want}${err}")
    endif()
    string(REGEX MATCH "halted after ([0-9]+) cycles" _ "${want}")
    set(want_cycles ${CMAKE_MATCH_1})
    string(REGEX REPLACE "^[^\n]*\n" "" want_state "${want}")
    if(NOT icarus_cycles STREQUAL want_cycles)
      message(FATAL_ERROR "${kernel}: Icarus halted after ${icarus_cycles} cycles, ${engine} after ${want_cycles}")
    endif()
    if(NOT icarus_state STREQUAL want_state)
      message(FATAL_ERROR "${kernel}: the end state under Icarus differs from ${engine}'s\n"
                          "Icarus:\n${icarus_state}\n${engine}:\n${want_state}")
    endif()
  endforeach()
  message(STATUS "apu_icarus: ${kernel}: ${icarus_cycles} cycles, the same end state as the ISS and the verilated core")
endfunction()

run(r_xform r_xform.apu 0x0 64 camera.hex end.hex)
run(xform4 xform4.apu 0x20 8 xform4.hex end.hex)
