# apu_hex(VALUE DIGITS OUT): VALUE in upper-case hex, zero-padded to DIGITS,
# the form GTKWave translate filters key on (apu_gtkwgen.cmake writes it,
# apu_gtkw_test.cmake looks it up).
function(apu_hex value digits out)
  math(EXPR hex "${value}" OUTPUT_FORMAT HEXADECIMAL)
  string(SUBSTRING "${hex}" 2 -1 hex)
  string(TOUPPER "${hex}" hex)
  string(LENGTH "${hex}" len)
  while(len LESS digits)
    string(PREPEND hex "0")
    math(EXPR len "${len} + 1")
  endwhile()
  set(${out} "${hex}" PARENT_SCOPE)
endfunction()
