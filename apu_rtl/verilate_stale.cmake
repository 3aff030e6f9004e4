# verilate() (verilator-config.cmake) keeps the source list of its last
# Verilator run in <prefix>_copy.cmake and, at configure time, runs Verilator
# again only when its arguments change. Once a .sv file is removed, that list
# names a file that no longer exists and the generate step fails. Dropping
# such a stale list makes the next verilate() run Verilator afresh.
# Included before the first verilate() call (apu_rtl, then hw/apu_rtl_engine).
file(GLOB_RECURSE verilate_copies ${CMAKE_BINARY_DIR}/*_copy.cmake)
foreach(copy ${verilate_copies})
  file(STRINGS ${copy} deps_line REGEX "_DEPS ")
  string(REGEX MATCHALL "\"[^\"]+\"" deps "${deps_line}")
  foreach(dep ${deps})
    string(REPLACE "\"" "" dep ${dep})
    if(NOT EXISTS ${dep})
      message(STATUS "verilate: ${dep} is gone, Verilator runs again (${copy})")
      file(REMOVE ${copy})
      break()
    endif()
  endforeach()
endforeach()
