# CTest check apu_icarus_engine_errors (docs/apu-rtl.md "Second simulator"):
# the icarus engine's failures, each a clear message naming what and where.
#   cmake -DIVERILOG=... -DAPU_COSIM=... -DSOURCE_DIR=<project> -DGENERATED=<build>/generated
#         -DWORK=<dir> -P apu_icarus_errors.cmake
# 1. no vvp file ($MC1_ICARUS_VVP names none): exit 2, the file named;
# 2. a vvp file that is not one (vvp ends at once): exit 2, vvp's own words;
# 3. a core whose bench ends in a cycle ($finish at the first XOR issued):
#    exit 1, the cycle and pc, "exited";
# 4. a core with an assertion that fires (at the first XOR issued, in the
#    form apu_rtl/apu_assert.svh gives Icarus): exit 1, the rule's name, the
#    cycle, pc and disassembled word;
# 5. a core with a planted bug (XOR computed as OR): apu-cosim reports the
#    first divergence as for any engine (cycle, pc, word, both values: the
#    XOR's A register commit, in the cycle after its issue) and the command
#    that reruns the case;
# 6. dbg_unit_mismatch set (planted: at the first XOR issued), which a
#    netlist reports though it has no assertions: exit 1, cycle and pc.
# 3 to 6 are copies of apu_rtl/ with apu_core.sv changed, compiled by
# tb/apu_icarus.cmake's script form into their own vvp files.
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
set(script ${CMAKE_CURRENT_LIST_DIR}/apu_icarus.cmake)

# cosim(name rc regex... [ENV var=value] ARGS args...): apu-cosim's exit status
# must be rc and its output match every regex.
function(cosim name want_rc)
  cmake_parse_arguments(C "" "" "MATCH;ENV;ARGS" ${ARGN})
  execute_process(COMMAND ${CMAKE_COMMAND} -E env ${C_ENV} ${APU_COSIM} ${C_ARGS}
    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  set(all "${out}${err}")
  if(NOT rc EQUAL want_rc)
    message(FATAL_ERROR "${name}: apu-cosim ${C_ARGS} exited ${rc}, not ${want_rc}:\n${all}")
  endif()
  foreach(re IN LISTS C_MATCH)
    if(NOT all MATCHES "${re}")
      message(FATAL_ERROR "${name}: apu-cosim's output does not match '${re}':\n${all}")
    endif()
  endforeach()
  message(STATUS "${name}: as expected (exit ${rc}):\n${all}")
endfunction()

# planted(name pattern replacement): a copy of apu_rtl/ with apu_core.sv's
# `pattern` (a literal string, which must occur) replaced, compiled to
# ${WORK}/<name>.vvp.
function(planted name pattern replacement)
  set(dir ${WORK}/${name})
  file(MAKE_DIRECTORY ${dir})
  file(GLOB files ${SOURCE_DIR}/apu_rtl/*.sv ${SOURCE_DIR}/apu_rtl/*.svh)
  file(COPY ${files} DESTINATION ${dir})
  file(READ ${dir}/apu_core.sv text)
  string(FIND "${text}" "${pattern}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "${name}: apu_rtl/apu_core.sv no longer has '${pattern}': update ${CMAKE_CURRENT_LIST_FILE}")
  endif()
  string(REPLACE "${pattern}" "${replacement}" text "${text}")
  file(WRITE ${dir}/apu_core.sv "${text}")
  file(GLOB pkgs ${dir}/*_pkg.sv)
  file(GLOB mods ${dir}/*.sv)
  list(REMOVE_ITEM mods ${pkgs})
  execute_process(COMMAND ${CMAKE_COMMAND} -DIVERILOG=${IVERILOG} -DSOURCE_DIR=${SOURCE_DIR} -DGENERATED=${GENERATED}
                          "-DCORE=${pkgs};${mods}" -DOUTPUT=${WORK}/${name}.vvp -P ${script}
    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${name}: compiling the planted core failed:\n${out}${err}")
  endif()
endfunction()

# 1. No vvp file.
cosim(missing_vvp 2 ENV MC1_ICARUS_VVP=${WORK}/missing.vvp ARGS --random 1 --engines iss,icarus
      MATCH "icarus engine: vvp file '[^']*missing.vvp' not found")

# 2. Not a vvp file: vvp refuses it at once.
file(WRITE ${WORK}/garbage.vvp "this is no vvp file\n")
cosim(not_vvp 2 ARGS --random 1 --engines iss,icarus --icarus-vvp ${WORK}/garbage.vvp
      MATCH "icarus engine: vvp [^ ]*garbage.vvp exited with status [0-9]+ at its start")

# 3. The bench ends in a cycle: $finish at the first XOR issued.
planted(ends "endmodule" "  always @(posedge clk) if (rst_n && issue && w.i_op == apu_pkg::I_XOR) $finish;  // planted
endmodule")
cosim(bench_ends 1 ARGS --random 30 --seed 1 --engines iss,icarus --icarus-vvp ${WORK}/ends.vvp
      MATCH "apu-cosim: icarus failed\n" "vvp [^ ]*ends.vvp exited with status 0 in cycle [0-9]+"
            "rerun: apu-cosim --random 1")

# 4. An assertion fires at the first XOR issued, in the form
# apu_rtl/apu_assert.svh gives Icarus.
planted(asserts "endmodule" "  always @(posedge clk)  // planted
    if (rst_n) assert (!(issue && w.i_op == apu_pkg::I_XOR)) else $error(\"APU_ASSERT PlantedXor failed in %m\");
endmodule")
cosim(assertion 1 ARGS --random 30 --seed 1 --engines iss,icarus --icarus-vvp ${WORK}/asserts.vvp
      MATCH "apu-cosim: icarus failed at cycle [0-9]+, pc 0x[0-9a-f]+ \\(bank [01]\\): [^\n]*xor"
            "the simulation reports an error in cycle [0-9]+, pc 0x[0-9a-f]+"
            "ERROR: [^\n]*APU_ASSERT PlantedXor failed" "rerun: apu-cosim --random 1")

# 5. A planted bug: XOR computed as OR.
planted(xor_or "alu_result = aop[AR_S] ^ aop[AR_T];" "alu_result = aop[AR_S] | aop[AR_T];  // planted bug")
cosim(divergence 1 ARGS --random 30 --seed 1 --engines iss,icarus --icarus-vvp ${WORK}/xor_or.vvp
      MATCH "apu-cosim: divergence at cycle [0-9]+, pc 0x[0-9a-f]+ \\(bank [01]\\): [^\n]+"
            "  commit [0-9]+: iss A[0-9]+=0x[0-9a-f]+  vs  icarus A[0-9]+=0x[0-9a-f]+"
            "rerun: apu-cosim --random 1 --seed 1 --first [0-9]+ --engines iss,icarus")

# 6. dbg_unit_mismatch set at the first XOR issued.
planted(mismatch "unit_mismatch_q <= unit_mismatch_q || unit_mismatch;"
        "unit_mismatch_q <= unit_mismatch_q || unit_mismatch || (issue && w.i_op == apu_pkg::I_XOR);  // planted")
cosim(unit_mismatch 1 ARGS --random 30 --seed 1 --engines iss,icarus --icarus-vvp ${WORK}/mismatch.vvp
      MATCH "apu-cosim: icarus failed at cycle [0-9]+, pc 0x[0-9a-f]+ \\(bank [01]\\): [^\n]*xor"
            "icarus engine: dbg_unit_mismatch after cycle [0-9]+, pc 0x[0-9a-f]+: a unit's result came out of step"
            "rerun: apu-cosim --random 1")
