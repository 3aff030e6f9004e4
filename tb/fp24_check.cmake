# CTest check of golden files (docs/fp24-verification.md, "Golden files"):
# fp24_known.vec zipped with fp24_known.expected is a golden file every engine
# agrees with; the same file with one planted wrong value reports exactly that
# line, on every engine, with the values decoded, and exit 1; fp24-regress
# --vectors finds the same line; a malformed line is exit 2 naming file:line;
# fp24-conv converts by the spec's rounding rule.
#   cmake -DRUN=fp24-run -DREGRESS=fp24-regress -DCONV=fp24-conv -DVECTORS=dir -DWORK_DIR=dir -P fp24_check.cmake
file(MAKE_DIRECTORY ${WORK_DIR})
file(STRINGS ${VECTORS}/fp24_known.vec vec)
file(STRINGS ${VECTORS}/fp24_known.expected expected)
set(golden "# fp24_known.vec with fp24_known.expected: op a [b] result flags\n")
set(k 0)
foreach(line IN LISTS vec)
  if(line MATCHES "^#" OR line MATCHES "^[ \t]*$")
    string(APPEND golden "${line}\n")
  else()
    list(GET expected ${k} result)
    math(EXPR k "${k} + 1")
    string(APPEND golden "${line} ${result}\n")
  endif()
endforeach()
file(WRITE ${WORK_DIR}/known.golden "${golden}")

# run(NAME RC regex-on-stdout [ERR regex] ARGS ...)
function(run name want_rc out_re)
  cmake_parse_arguments(R "" "ERR" "ARGS" ${ARGN})
  execute_process(COMMAND ${R_ARGS} WORKING_DIRECTORY ${WORK_DIR}
    OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE rc)
  if(NOT rc EQUAL want_rc OR NOT out MATCHES "${out_re}" OR (DEFINED R_ERR AND NOT err MATCHES "${R_ERR}"))
    message(SEND_ERROR "${name}: exit ${rc} (wanted ${want_rc})\nstdout: ${out}\nstderr: ${err}\n"
                       "wanted stdout ~ '${out_re}', stderr ~ '${R_ERR}'")
  endif()
  set(last_out "${out}" PARENT_SCOPE)
endfunction()

run(all_agree 0 "known.golden: ${k} vectors, 0 mismatches: PASS\n$" ARGS ${RUN} --check known.golden)
# The same from standard input, upper-case ops and 0x prefixes.
string(REPLACE "mul " "MUL 0x" shouted "${golden}")
file(WRITE ${WORK_DIR}/shouted.golden "${shouted}")
run(stdin_prefixes 0 "<stdin>: ${k} vectors, 0 mismatches: PASS" ARGS ${RUN} --check - --engine model
    INPUT_FILE ${WORK_DIR}/shouted.golden)

# Plant one wrong value: mul 408000 408000 is 3 * 3 = 9 (422000), not 8.
string(REPLACE "mul 408000 408000 422000 00" "mul 408000 408000 420000 00" planted "${golden}")
if(planted STREQUAL golden)
  message(FATAL_ERROR "the planted line is not in fp24_known.vec/.expected any more")
endif()
file(WRITE ${WORK_DIR}/planted.golden "${planted}")
string(REGEX MATCH "^(.*\n)?mul 408000 408000 420000" before "${planted}")
string(REGEX MATCHALL "\n" newlines "${before}")
list(LENGTH newlines n)
math(EXPR line "${n} + 1")
set(located "planted.golden:${line}: ENGINE: mul 408000 408000 \\(3, 3\\): expected 420000 00 \\(8; -\\), got 422000 00 \\(9; -\\)\n")
foreach(engine model rtl oracle)
  string(REPLACE ENGINE ${engine} want "${located}")
  run(planted_${engine} 1 "^${want}summary by op" ARGS ${RUN} --check planted.golden --engine ${engine})
  string(REGEX MATCHALL "planted.golden:[0-9]+:" hits "${last_out}")
  list(LENGTH hits nhits)
  if(NOT nhits EQUAL 1)
    message(SEND_ERROR "planted_${engine}: ${nhits} located lines, wanted exactly 1\n${last_out}")
  endif()
endforeach()
# On all three engines: one line naming the three (the same wrong result),
# one mismatch (a vector, not a vector per engine), per-engine counts in the summary.
string(REPLACE ENGINE "model, rtl, oracle" want "${located}")
run(planted_all 1 "^${want}summary by op.*  mul +[0-9]+ +1 +1 +1\n.*model: result value 1, NV 0/0.*planted.golden: ${k} vectors, 1 mismatch: FAIL\n$"
    ARGS ${RUN} --check planted.golden)
run(regress_vectors 1 "model-vs-golden: planted.golden:${line}: model: mul 408000 408000 \\(3, 3\\)"
    ARGS ${REGRESS} --vectors planted.golden --threads 1)
run(regress_vectors_pass 0 "known.golden, ${k} vectors.*PASS\n$" ARGS ${REGRESS} --vectors known.golden --threads 1)

# Bad input: exit 2, nothing on stdout, file:line on stderr.
file(WRITE ${WORK_DIR}/bad.golden "add 3f0000 3f0000 400000 00\nadd 3f0000 3f0000 400000\n")
run(missing_flags 2 "^$" ERR "^bad.golden:2: add wants 2 operand\\(s\\), a result and flags: 5 fields, got 4"
    ARGS ${RUN} --check bad.golden)
file(WRITE ${WORK_DIR}/bad_flags.golden "neg 3f0000 bf0000 20\n")
run(flags_range 2 "^$" ERR "^bad_flags.golden:1: flags '20' is out of range \\(max 1f\\)" ARGS ${RUN} --check bad_flags.golden)
run(no_file 2 "^$" ERR "--check: none.golden: No such file" ARGS ${RUN} --check none.golden)
run(all_without_check 2 "^$" ERR "--engine all needs --check" ARGS ${RUN} --engine all)
run(regress_bad 2 "^$" ERR "^bad.golden:2: " ARGS ${REGRESS} --vectors bad.golden)

# fp24-conv: decimal to FP24 by the rounding rule, back, and flags.
run(conv_exact 0 "^1.5: 3f8000 flags 00 \\(-\\), reads back 1.5\n$" ARGS ${CONV} 1.5)
run(conv_inexact 0 "^0.1: 3b999a flags 01 \\(NX\\), reads back 0.1\n$" ARGS ${CONV} 0.1)
run(conv_overflow 0 "^1e30: 7f0000 flags 05 \\(OF\\|NX\\)" ARGS ${CONV} 1e30)
run(conv_underflow 0 "^1e-30: 000000 flags 03 \\(UF\\|NX\\)" ARGS ${CONV} 1e-30)
run(conv_negative 0 "^-2: c00000 flags 00" ARGS ${CONV} -- -2)
run(conv_hex 0 "^3f8000: 1.5 \\(s 0 e 63 f 8000\\)\n$" ARGS ${CONV} 0x3f8000)
run(conv_daz 0 "^000012: 0 \\(DAZ\\)" ARGS ${CONV} 0x000012)
run(conv_flags 0 "^NV\\|NX: 11 \\(NV\\|NX\\)\n0x05: 05 \\(OF\\|NX\\)\n$" ARGS ${CONV} --flags NV|NX 0x05)
run(conv_flags_commas 0 "^nv,dz: 18 \\(NV\\|DZ\\)\n$" ARGS ${CONV} --flags nv,dz)
run(conv_bad 2 "^$" ERR "VALUE '1.5x': not a decimal number" ARGS ${CONV} 1.5x)
