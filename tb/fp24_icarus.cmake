# CTest check (docs/fp24-verification.md "Second simulator"): the FP24 RTL,
# compiled unmodified with Icarus Verilog, gives the same bits and flags as
# the verilated RTL and the C++ model.
#   cmake -DIVERILOG=... -DVVP=... -DPYTHON=... -DFP24_RUN=... -DSOURCE_DIR=<project>
#         -DGENERATED=<build>/generated -DWORK=<dir> -DCOUNT=<vectors per op> -DSEED=<n>
#         -P fp24_icarus.cmake
# 1. iverilog -g2012 of tb/fp24_icarus_tb.sv and apu_rtl/fp24_*.sv;
# 2. tb/vectors/fp24_known.vec must give fp24_known.expected;
# 3. COUNT random vectors per op (tb/fp24_icarus_vectors.py): Icarus, the
#    verilated RTL and the model must agree on every line.
file(MAKE_DIRECTORY ${WORK})
set(rtl ${SOURCE_DIR}/apu_rtl)
file(GLOB packages ${rtl}/fp24_*pkg.sv)
file(GLOB units ${rtl}/fp24_*.sv)
list(REMOVE_ITEM units ${packages})
set(vvp_file ${WORK}/fp24_icarus.vvp)
execute_process(COMMAND ${IVERILOG} -g2012 -I${GENERATED} -I${rtl} -s fp24_icarus_tb -o ${vvp_file}
                        ${GENERATED}/apu_pkg.sv ${packages} ${SOURCE_DIR}/tb/fp24_icarus_tb.sv ${units}
  RESULT_VARIABLE rc ERROR_VARIABLE err OUTPUT_VARIABLE out)
if(NOT rc EQUAL 0 OR err MATCHES "error")
  message(FATAL_ERROR "iverilog -g2012 failed (exit ${rc}):\n${out}${err}")
endif()

# Runs the Icarus bench on `input`, the result in `output`.
function(run_icarus input output)
  execute_process(COMMAND ${VVP} -n ${vvp_file} +vectors=${input} +results=${output}
    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0 OR out MATCHES "FATAL|ERROR" OR NOT EXISTS ${output})
    message(FATAL_ERROR "vvp fp24_icarus_tb on ${input} failed (exit ${rc}):\n${out}${err}")
  endif()
endfunction()

# Fails naming the first vector where `got` (from `who`) differs from `want`.
function(compare vectors want got who)
  file(STRINGS ${want} want_lines)
  file(STRINGS ${got} got_lines)
  list(LENGTH want_lines n_want)
  list(LENGTH got_lines n_got)
  if(NOT n_want EQUAL n_got)
    message(FATAL_ERROR "${who}: ${n_got} results, ${want} has ${n_want}")
  endif()
  file(READ ${want} want_text)
  file(READ ${got} got_text)
  if(want_text STREQUAL got_text)
    return()
  endif()
  # The first differing line, with its vector (a CMake list walk of 10^5
  # lines is quadratic).
  execute_process(COMMAND ${PYTHON} -c [=[
import re, sys
vec = [l.strip() for l in open(sys.argv[1]) if re.match(r"\s*[a-z]", l)]
for i, (w, g) in enumerate(zip(open(sys.argv[2]), open(sys.argv[3]))):
    if w != g:
        print(f"result {i + 1} (`{vec[i]}`): got {g.strip()}, want {w.strip()}")
        break
]=] ${vectors} ${want} ${got} OUTPUT_VARIABLE first)
  message(FATAL_ERROR "${who}: ${first}")
endfunction()

set(known ${SOURCE_DIR}/tb/vectors/fp24_known.vec)
run_icarus(${known} ${WORK}/known.icarus)
compare(${known} ${SOURCE_DIR}/tb/vectors/fp24_known.expected ${WORK}/known.icarus
        "Icarus on fp24_known.vec vs fp24_known.expected")

set(random ${WORK}/random.vec)
execute_process(COMMAND ${PYTHON} ${SOURCE_DIR}/tb/fp24_icarus_vectors.py ${COUNT} ${SEED}
  OUTPUT_FILE ${random} RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "fp24_icarus_vectors.py ${COUNT} ${SEED} failed (exit ${rc})")
endif()
foreach(engine rtl model)
  execute_process(COMMAND ${FP24_RUN} --engine ${engine} INPUT_FILE ${random}
    OUTPUT_FILE ${WORK}/random.${engine} RESULT_VARIABLE rc ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "fp24-run --engine ${engine} < ${random}: exit ${rc}\n${err}")
  endif()
endforeach()
run_icarus(${random} ${WORK}/random.icarus)
compare(${random} ${WORK}/random.rtl ${WORK}/random.icarus "Icarus vs the verilated RTL")
compare(${random} ${WORK}/random.model ${WORK}/random.icarus "Icarus vs the model")
file(STRINGS ${random} all)
list(LENGTH all n)
message(STATUS "fp24_icarus: ${n} random vectors (${COUNT} per op) and fp24_known.vec agree")
