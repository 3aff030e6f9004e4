# Generator of GTKWave translate filters from the instruction-set table
# (docs/apu-rtl.md "Waveforms"): one file per enum of apu_isa.tbl (the
# slots' op fields, stall reason, run state, fault), mapping each code, as
# GTKWave prints it in hex, to the name the assembler and the reports use.
# The save files docs/*.gtkw load them, so a trace opens with names.
#
#   cmake -DTABLE=<apu_isa.tbl> -DOUT_DIR=<dir> -P apu_gtkwgen.cmake
#
# Writes OUT_DIR/<SV enum type>.txt (add_op_e.txt, stall_e.txt, ...); a file
# is rewritten only when its content changes. apu_isagen.cmake checks the
# table; this reads only its enum and value records.
include(${CMAKE_CURRENT_LIST_DIR}/apu_hex.cmake)
cmake_minimum_required(VERSION 3.22)
if(NOT TABLE OR NOT OUT_DIR)
  message(FATAL_ERROR "usage: cmake -DTABLE=<apu_isa.tbl> -DOUT_DIR=<dir> -P apu_gtkwgen.cmake")
endif()

file(STRINGS "${TABLE}" lines)
set(enums)
foreach(line IN LISTS lines)
  string(REGEX REPLACE "#.*" "" line "${line}")
  string(REGEX REPLACE "[ \t]+" ";" tok "${line}")
  list(FILTER tok EXCLUDE REGEX "^$")
  list(LENGTH tok n)
  if(n EQUAL 0)
    continue()
  endif()
  list(GET tok 0 kind)
  if(kind STREQUAL "enum")
    list(GET tok 1 cur)
    list(GET tok 3 bits)
    list(APPEND enums ${cur})
    set(bits_${cur} ${bits})
    set(text_${cur} "# GTKWave translate filter for ${cur} (${bits} bits), generated from apu_isa.tbl by\n# apu_rtl/isa/apu_gtkwgen.cmake: the code in hex as GTKWave prints it, then its name.\n")
  elseif(kind STREQUAL "value")
    list(GET tok 1 sv)
    list(GET tok 2 cpp)
    list(GET tok 3 code)
    list(GET tok 4 name)
    if(name STREQUAL "-")  # the empty slot: its C++ name, in lower case
      string(TOLOWER "${cpp}" name)
    endif()
    math(EXPR digits "(${bits_${cur}} + 3) / 4")
    apu_hex("${code}" ${digits} hex)
    string(APPEND text_${cur} "${hex} ${name}\n")
  elseif(kind STREQUAL "slot")
    break()  # the enums come first in the table
  endif()
endforeach()

file(MAKE_DIRECTORY "${OUT_DIR}")
foreach(e IN LISTS enums)
  set(path "${OUT_DIR}/${e}.txt")
  if(EXISTS "${path}")
    file(READ "${path}" old)
    if(old STREQUAL text_${e})
      continue()
    endif()
  endif()
  file(WRITE "${path}" "${text_${e}}")
endforeach()
