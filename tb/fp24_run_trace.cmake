# CTest check: `fp24-run --engine rtl --trace FILE` writes an FST of
# fp24_units, and every signal the GTKWave save file names is in it.
#   cmake -DPROGRAM=... -DINPUT=... -DFST=... -DGTKW=... [-DFST2VCD=...] -P fp24_run_trace.cmake
file(REMOVE ${FST})
execute_process(COMMAND ${PROGRAM} --engine rtl --trace ${FST}
  INPUT_FILE ${INPUT} OUTPUT_QUIET ERROR_VARIABLE err RESULT_VARIABLE rc)
if(NOT rc EQUAL 0 OR NOT EXISTS ${FST})
  message(FATAL_ERROR "fp24-run --trace ${FST}: exit ${rc}\n${err}")
endif()
if(NOT FST2VCD)
  message(STATUS "fst2vcd (gtkwave) not found: signal names not checked")
  return()
endif()

# Full names (TOP.fp24_units.u_mul.s1_valid, with [msb:lsb] for vectors) of
# every variable in the VCD header.
execute_process(COMMAND ${FST2VCD} ${FST} OUTPUT_VARIABLE vcd ERROR_QUIET)
string(FIND "${vcd}" "$enddefinitions" end)
string(SUBSTRING "${vcd}" 0 ${end} header)
# A variable's id code is any printable character sequence, `;` `[` `]`
# included, which CMake lists would split or group on: drop them first.
string(REGEX REPLACE "\\$var ([a-z]+) ([0-9]+) [^ ]+ " "$var \\1 \\2 - " header "${header}")
string(REGEX MATCHALL "\\$(scope [a-z]+ [^ ]+|upscope|var [a-z]+ [0-9]+ [^ ]+ [^ ]+( \\[[0-9:]+\\])?) " tokens "${header}")
set(scope "")
set(names "")
foreach(t ${tokens})
  if(t MATCHES "^\\$scope [a-z]+ ([^ ]+) $")
    list(APPEND scope ${CMAKE_MATCH_1})
  elseif(t MATCHES "^\\$upscope")
    list(POP_BACK scope)
  elseif(t MATCHES "^\\$var [a-z]+ [0-9]+ [^ ]+ ([^ ]+)( (\\[[0-9:]+\\]))? $")
    list(JOIN scope "." path)
    list(APPEND names "${path}.${CMAKE_MATCH_1}${CMAKE_MATCH_3}")
  endif()
endforeach()

file(STRINGS ${GTKW} wanted REGEX "^TOP\\.")
foreach(signal ${wanted})
  list(FIND names "${signal}" at)
  if(at EQUAL -1)
    message(SEND_ERROR "${GTKW} names ${signal}, which ${FST} does not have")
  endif()
endforeach()
list(LENGTH wanted count)
message(STATUS "${count} signals of ${GTKW} found in ${FST}")
