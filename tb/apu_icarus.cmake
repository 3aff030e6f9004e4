# The APU core under Icarus Verilog, the second simulator (docs/apu-rtl.md
# "Second simulator"): IcarusEngine (tb/apu/apu_icarus_engine.{hpp,cpp})
# runs tb/apu/apu_icarus_lockstep_tb.sv under vvp behind ApuEngine, so that
# apu-cosim runs the core under Icarus in lockstep with the ISS.
#
# Two uses of this file:
#
# 1. Script: compile a vvp file of the bench with an apu_core.
#      cmake -DIVERILOG=iverilog -DSOURCE_DIR=<project> -DGENERATED=<build>/generated
#            -DOUTPUT=<file.vvp> [-DCORE=<a.v;b.sv;...>] [-DDEFINES=APU_NETLIST;...]
#            -P tb/apu_icarus.cmake
#    Without CORE: the RTL (apu_rtl/*.sv). With CORE: those files are the
#    core instead (a module named apu_core with its ports; a flattened Yosys
#    netlist with DEFINES=APU_NETLIST, whose memories the bench reaches by
#    their flattened names). The package apu_pkg.sv (the bench's sizes) is
#    always read. iverilog's own notes ("sorry: ... ignored") are printed
#    only on a failure.
#
# 2. include()d by tb/apu/CMakeLists.txt: the build's vvp file
#    (apu_icarus_core.vvp, target apu_icarus_vvp), the engine library
#    apu_icarus_engine linked into apu-cosim, apu-run and apu-bench, and
#    the tests (labels default and long).

if(CMAKE_SCRIPT_MODE_FILE)
  foreach(v IVERILOG SOURCE_DIR GENERATED OUTPUT)
    if(NOT DEFINED ${v})
      message(FATAL_ERROR "apu_icarus.cmake: -D${v}=... missing")
    endif()
  endforeach()
  set(rtl ${SOURCE_DIR}/apu_rtl)
  file(GLOB packages ${rtl}/*_pkg.sv)
  if(DEFINED CORE AND NOT CORE STREQUAL "")
    set(core ${CORE})
    set(packages "")  # a netlist has no packages (the FP24 unit's is folded in)
  else()
    file(GLOB core ${rtl}/*.sv)
    list(REMOVE_ITEM core ${packages})
  endif()
  set(defs "")
  foreach(d IN LISTS DEFINES)
    list(APPEND defs -D${d})
  endforeach()
  get_filename_component(out_dir ${OUTPUT} DIRECTORY)
  file(MAKE_DIRECTORY ${out_dir})
  execute_process(
    COMMAND ${IVERILOG} -g2012 ${defs} -I${GENERATED} -I${rtl} -s apu_icarus_lockstep_tb -o ${OUTPUT}.tmp
            ${GENERATED}/apu_pkg.sv ${packages} ${SOURCE_DIR}/tb/apu/apu_icarus_lockstep_tb.sv ${core}
    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0 OR NOT EXISTS ${OUTPUT}.tmp)
    file(REMOVE ${OUTPUT}.tmp)
    message(FATAL_ERROR "iverilog -g2012 of the Icarus bench failed (exit ${rc}):\n${out}${err}")
  endif()
  file(RENAME ${OUTPUT}.tmp ${OUTPUT})
  return()
endif()

# ---- included by tb/apu/CMakeLists.txt --------------------------------------------

find_program(IVERILOG iverilog)
find_program(VVP vvp)

add_library(apu_icarus_engine STATIC ${CMAKE_CURRENT_LIST_DIR}/apu/apu_icarus_engine.cpp)
target_include_directories(apu_icarus_engine PUBLIC ${CMAKE_CURRENT_LIST_DIR}/apu)
target_link_libraries(apu_icarus_engine PUBLIC apu_core)
set(APU_ICARUS_VVP_FILE "")
if(IVERILOG AND VVP)
  set(APU_ICARUS_VVP_FILE ${CMAKE_CURRENT_BINARY_DIR}/apu_icarus_core.vvp)
  file(GLOB APU_ICARUS_RTL ${PROJECT_SOURCE_DIR}/apu_rtl/*.sv ${PROJECT_SOURCE_DIR}/apu_rtl/*.svh)
  add_custom_command(OUTPUT ${APU_ICARUS_VVP_FILE}
    COMMAND ${CMAKE_COMMAND} -DIVERILOG=${IVERILOG} -DSOURCE_DIR=${PROJECT_SOURCE_DIR}
            -DGENERATED=${MC1_GENERATED_DIR} -DOUTPUT=${APU_ICARUS_VVP_FILE}
            -P ${CMAKE_CURRENT_LIST_FILE}
    DEPENDS ${CMAKE_CURRENT_LIST_FILE} ${CMAKE_CURRENT_LIST_DIR}/apu/apu_icarus_lockstep_tb.sv
            ${APU_ICARUS_RTL} ${MC1_GENERATED_DIR}/apu_pkg.sv ${MC1_GENERATED_DIR}/apu_microword.svh fp24_rom
    COMMENT "iverilog: the APU core's Icarus bench (apu_icarus_core.vvp)"
    VERBATIM)
  add_custom_target(apu_icarus_vvp ALL DEPENDS ${APU_ICARUS_VVP_FILE})
  add_dependencies(apu_icarus_engine apu_icarus_vvp)
  target_compile_definitions(apu_icarus_engine PRIVATE MC1_ICARUS_VVP_FILE="${APU_ICARUS_VVP_FILE}"
                                                       MC1_VVP_PROGRAM="${VVP}")
else()
  message(WARNING "iverilog/vvp not found: the icarus engine has no vvp file, no apu_icarus tests "
                  "(tools/setup.sh installs iverilog)")
endif()
foreach(tool apu-cosim apu-run apu-bench)
  target_link_libraries(${tool} PRIVATE apu_icarus_engine)
endforeach()

if(IVERILOG AND VVP)
  set(APU_ICARUS_WORK ${CMAKE_CURRENT_BINARY_DIR}/apu_icarus)
  file(MAKE_DIRECTORY ${APU_ICARUS_WORK})
  # The two kernels the first Icarus bench ran (to the same end state), now
  # in lockstep with the ISS, every cycle compared.
  # r_xform's camera batch (firmware/kernels/r_layout.inc): COUNT 1,
  # XM_CAMERA, eye (0, 0, 5), look-at the origin, up (0, 1, 0), 60 degrees,
  # 96x64, pi/360; then the end of the stream. It runs MUL, ADD, SUB, NEG,
  # FLOAT, RECIP, SQRT, SIN and COS, LD/ST, CALL/RET and two SWAPDs.
  file(WRITE ${APU_ICARUS_WORK}/camera.hex "@0 000001 000000\n@b 414000 000000 000000\n"
             "@10 000000 000000 000000 000000 3f0000 000000 44e000 000060 000040 381df4\n")
  file(WRITE ${APU_ICARUS_WORK}/end.hex "@0 000000\n")
  # xform4 (docs/apu-tools.md): one block of two vertices, a DBNZ loop.
  file(WRITE ${APU_ICARUS_WORK}/xform4.hex "@0 000002\n@10 400000 000000 000000 3f0000\n000000 400000 000000 400000\n"
             "000000 000000 400000 000000\n000000 000000 000000 3f0000\n"
             "@20 3f0000 400000 408000 3f0000\nbf0000 000000 3f0000 3f0000\n")
  add_test(NAME apu_icarus_r_xform
    COMMAND apu-cosim ${PROJECT_SOURCE_DIR}/firmware/kernels/r_xform.apu --data ${APU_ICARUS_WORK}/camera.hex
            --data ${APU_ICARUS_WORK}/end.hex --engines iss,icarus)
  set_tests_properties(apu_icarus_r_xform PROPERTIES PASS_REGULAR_EXPRESSION "agree on [0-9]+ cycles; halted")
  add_test(NAME apu_icarus_xform4
    COMMAND apu-cosim ${PROJECT_SOURCE_DIR}/firmware/kernels/xform4.apu --data ${APU_ICARUS_WORK}/xform4.hex
            --data ${APU_ICARUS_WORK}/end.hex --engines iss,icarus)
  set_tests_properties(apu_icarus_xform4 PROPERTIES PASS_REGULAR_EXPRESSION "agree on [0-9]+ cycles; halted")
  # Random programs (apu_random.hpp, with their MPU hand-over schedules)
  # in lockstep, ISS against apu_core under Icarus: about 0.5 s of host CPU
  # a program (Icarus simulates the core at about 1000 cycles a second), so
  # the runs are split in shards ctest runs in parallel. Default: 300
  # programs of seed 1 in 2 shards; long: 6000 of seed 3 in 4.
  foreach(first 0 150)
    add_test(NAME apu_icarus_cosim_random_${first}
      COMMAND apu-cosim --random 150 --seed 1 --first ${first} --engines iss,icarus)
    set_tests_properties(apu_icarus_cosim_random_${first} PROPERTIES LABELS default TIMEOUT 900)
  endforeach()
  foreach(first 0 1500 3000 4500)
    add_test(NAME apu_icarus_cosim_random_long_${first}
      COMMAND apu-cosim --random 1500 --seed 3 --first ${first} --engines iss,icarus)
    set_tests_properties(apu_icarus_cosim_random_long_${first} PROPERTIES LABELS long TIMEOUT 7200)
  endforeach()
  set_tests_properties(apu_icarus_r_xform apu_icarus_xform4 PROPERTIES LABELS default TIMEOUT 120)
  # The engine's failures, each named: no vvp file, a bench that ends, an
  # assertion line, a core with a planted bug (a divergence as apu-cosim
  # reports it).
  add_test(NAME apu_icarus_engine_errors
    COMMAND ${CMAKE_COMMAND} -DIVERILOG=${IVERILOG} -DAPU_COSIM=$<TARGET_FILE:apu-cosim>
            -DSOURCE_DIR=${PROJECT_SOURCE_DIR} -DGENERATED=${MC1_GENERATED_DIR}
            -DWORK=${CMAKE_CURRENT_BINARY_DIR}/apu_icarus_errors
            -P ${CMAKE_CURRENT_LIST_DIR}/apu_icarus_errors.cmake)
  set_tests_properties(apu_icarus_engine_errors PROPERTIES LABELS default TIMEOUT 300)
endif()
