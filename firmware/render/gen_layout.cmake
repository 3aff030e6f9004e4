# cmake -DIN=r_layout.inc -DOUT=render_layout.hpp -P gen_layout.cmake
# The MPU firmware's copy of the kernels' data-bank layout: every
# `.equ NAME, value  # comment` line of IN becomes a C++ constant, so the
# firmware and the microcode read one definition.
file(STRINGS ${IN} lines)
set(body "")
foreach(line IN LISTS lines)
  if(line MATCHES "^[ \t]*\\.equ[ \t]+([A-Za-z_][A-Za-z0-9_]*),[ \t]*([0-9xXa-fA-F]+)[ \t]*(#(.*))?$")
    set(name ${CMAKE_MATCH_1})
    set(value ${CMAKE_MATCH_2})
    string(STRIP "${CMAKE_MATCH_4}" comment)
    if(comment)
      string(APPEND body "constexpr int ${name} = ${value};  // ${comment}\n")
    else()
      string(APPEND body "constexpr int ${name} = ${value};\n")
    endif()
  endif()
endforeach()
file(WRITE ${OUT}.tmp "// Generated from ${IN} by firmware/render/gen_layout.cmake; do not edit.\n"
  "#pragma once\n\nnamespace mc1::render::layout {\n\n${body}\n}  // namespace mc1::render::layout\n")
file(COPY_FILE ${OUT}.tmp ${OUT} ONLY_IF_DIFFERENT)
