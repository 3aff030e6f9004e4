# cmake -DIN=r_layout.inc -DOUT=render_layout.hpp -P gen_layout.cmake
# The MPU firmware's view of the kernels' interface: every
# `.equ NAME, expr  # comment` line of IN becomes `constexpr int NAME = expr;`
# and every comment line a comment, so that firmware and microcode read one
# definition. The expressions are copied as written: they must mean the same
# in both languages (numbers, names above, ( ) + - * / << >>). Any other line
# is an error naming IN:line (a message that begins with a space is not
# wrapped by CMake, so the file:line stays whole).
file(STRINGS ${IN} lines)
set(body "")
set(n 0)
foreach(line IN LISTS lines)
  math(EXPR n "${n} + 1")
  if(line MATCHES "^[ \t]*\\.equ[ \t]+([A-Za-z_][A-Za-z0-9_]*),[ \t]*([^#]*[^# \t])[ \t]*(#(.*))?$")
    set(name ${CMAKE_MATCH_1})
    set(value ${CMAKE_MATCH_2})
    string(STRIP "${CMAKE_MATCH_4}" comment)
    if(value MATCHES "[^A-Za-z0-9_xX+*/()<> \t-]")
      message(FATAL_ERROR " ${IN}:${n}: '${value}' is not an expression both the assembler and C++ read alike")
    endif()
    if(comment)
      string(APPEND body "constexpr int ${name} = ${value};  // ${comment}\n")
    else()
      string(APPEND body "constexpr int ${name} = ${value};\n")
    endif()
  elseif(line MATCHES "^#(.*)$")
    string(APPEND body "//${CMAKE_MATCH_1}\n")
  elseif(line MATCHES "^[ \t]*$")
    string(APPEND body "\n")
  else()
    message(FATAL_ERROR " ${IN}:${n}: not an .equ or a comment line: ${line}")
  endif()
endforeach()
file(WRITE ${OUT}.tmp "// Generated from ${IN} by firmware/render/gen_layout.cmake; do not edit.\n"
  "#pragma once\n\nnamespace mc1::render::layout {\n\n${body}\n}  // namespace mc1::render::layout\n")
file(COPY_FILE ${OUT}.tmp ${OUT} ONLY_IF_DIFFERENT)
