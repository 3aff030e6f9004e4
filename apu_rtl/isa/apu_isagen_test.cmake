# ctest apu_isagen_checks: the generator accepts the real table, writes its
# three files, and refuses a broken table with its file and line.
#   cmake -DTABLE=<apu_isa.tbl> -DGENERATOR=<apu_isagen.cmake> -DWORK=<dir> -P apu_isagen_test.cmake
cmake_minimum_required(VERSION 3.22)

function(generate table out_dir rc_var log_var)
  file(MAKE_DIRECTORY ${out_dir})
  execute_process(COMMAND ${CMAKE_COMMAND} -DTABLE=${table} -DPKG_SV=${out_dir}/apu_pkg.sv
                          -DMICROWORD_SVH=${out_dir}/apu_microword.svh
                          -DISA_HPP=${out_dir}/apu_isa.hpp -P ${GENERATOR}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE log ERROR_VARIABLE log)
  set(${rc_var} ${rc} PARENT_SCOPE)
  set(${log_var} "${log}" PARENT_SCOPE)
endfunction()

file(REMOVE_RECURSE ${WORK})
generate(${TABLE} ${WORK}/good rc log)
if(rc OR NOT EXISTS ${WORK}/good/apu_pkg.sv OR NOT EXISTS ${WORK}/good/apu_microword.svh
      OR NOT EXISTS ${WORK}/good/apu_isa.hpp)
  message(FATAL_ERROR "the real table does not generate:\n${log}")
endif()
file(READ ${WORK}/good/apu_isa.hpp hpp)
file(READ ${WORK}/good/apu_pkg.sv sv)
file(READ ${WORK}/good/apu_microword.svh svh)
foreach(expected "constexpr int kTrigLatency = 9;" "case FuncOp::Sin: return kTrigLatency;"
                 "visit(Field{118, 10}, w.s.target);" "constexpr int kStallKinds = 7;")
  string(FIND "${hpp}" "${expected}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "apu_isa.hpp lacks: ${expected}")
  endif()
endforeach()
foreach(expected "localparam int LAT_TRIG = 9;" "A_RSVD = 3'd7")
  string(FIND "${sv}" "${expected}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "apu_pkg.sv lacks: ${expected}")
  endif()
endforeach()
foreach(expected "logic [9:0] s_target;" "} microword_t;")
  string(FIND "${svh}" "${expected}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "apu_microword.svh lacks: ${expected}")
  endif()
endforeach()

# Each mutation of the table: the text it replaces, the text it puts there,
# the message the generator must give and, when that is not the edited line,
# the text of the line the message must name.
file(READ ${TABLE} text)
set(cases
  "field b       35   6  uint|field b       35   5  uint|field en starts at bit 41|field en      41"
  "value A_SUB   Sub       1|value A_SUB   Sub       0|value A_SUB repeats the code 0 of A_ADD"
  "value F_SIN   Sin       2  sin       TRIG|value F_SIN   Sin       2  sin       TRAG|'TRAG' is neither"
  "value S_HALT   Halt       12|value S_HALT   Halt       16|does not fit 4 bits"
  "unit TRIG   9|unit TRIG   nine|must be a decimal number"
  "field op     110   4  seq_op_e|field op     110   3  seq_op_e|seq_op_e is 4 bits wide"
  "value I_LI    Li|value S_JMP    Li|value S_JMP defined twice|value S_JMP    Jmp")
set(n 0)
foreach(case IN LISTS cases)
  string(REPLACE "|" ";" parts "${case}")
  list(GET parts 0 from)
  list(GET parts 1 to)
  list(GET parts 2 message)
  set(where "${from}")
  list(LENGTH parts nparts)
  if(nparts EQUAL 4)
    list(GET parts 3 where)
  endif()
  foreach(needle "${from}" "${where}")
    string(FIND "${text}" "${needle}" at)
    if(at EQUAL -1)
      message(FATAL_ERROR "test case out of date: the table has no '${needle}'")
    endif()
  endforeach()
  string(SUBSTRING "${text}" 0 ${at} before)
  string(REGEX MATCHALL "\n" newlines "${before}")
  list(LENGTH newlines line)
  math(EXPR line "${line} + 1")
  string(REPLACE "${from}" "${to}" bad "${text}")
  math(EXPR n "${n} + 1")
  set(bad_table ${WORK}/bad${n}.tbl)
  file(WRITE ${bad_table} "${bad}")
  generate(${bad_table} ${WORK}/bad${n} rc log)
  string(REGEX REPLACE "[ \t\n]+" " " log "${log}")
  if(NOT rc)
    message(FATAL_ERROR "'${to}' was accepted")
  endif()
  if(NOT log MATCHES "bad${n}\\.tbl:${line}: [^\n]*${message}")
    message(FATAL_ERROR "'${to}': expected 'bad${n}.tbl:${line}: ...${message}', got:\n${log}")
  endif()
endforeach()
message(STATUS "apu_isagen: the real table generates; ${n} broken tables refused with file:line")
