# CTest check of what fp24-regress refuses to read or to combine, each a
# usage or input error (exit 2) that names the file (FILE:LINE) or both
# options: a --vectors line over 4096 bytes and a --merge report over 64 MiB
# (files that never end, such as /dev/zero, stop there; mc1 sweep --merge
# reads its reports the same way); --vectors with an option that shapes the
# built-in sets, --merge with one of a run; and a shard report whose counts
# are not counts (negative, fractional, over 2^53, or their sum over the
# shards), whose op is unknown or listed twice, or whose "passed" is not
# what its counts say (a shard that failed must fail the merge).
#   cmake -DREGRESS=fp24-regress -DMC1=mc1 -DWORK_DIR=dir -P fp24_regress_inputs.cmake
include(${CMAKE_CURRENT_LIST_DIR}/fp24_cli_run.cmake)
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR})

# run(NAME RC ERR-regex PROGRAM ARGS...) in WORK_DIR.
function(run name want_rc err_re)
  run_in_work(${name} ${want_rc} "${err_re}" ${ARGN})
endfunction()

file(WRITE ${WORK_DIR}/g.golden "neg 3f0000\nadd 3f0000 3f0000 400000 00\n")
set(run ${REGRESS} --vectors g.golden --threads 1)

# ---- sizes ----
string(REPEAT "0" 4094 zeros)
file(WRITE ${WORK_DIR}/long_ok.golden "# ${zeros}\nneg 3f0000\n")  # a line of 4096 bytes: read
run(line_4096 0 "" ${REGRESS} --vectors long_ok.golden --threads 1)
file(WRITE ${WORK_DIR}/long.golden "neg 3f0000\n# ${zeros}0\n")
run(line_4097 2 "^long.golden:2: line longer than 4096 bytes" ${REGRESS} --vectors long.golden)
file(WRITE ${WORK_DIR}/no_newline.golden "${zeros}${zeros}")
run(line_no_newline 2 "^no_newline.golden:1: line longer than 4096 bytes" ${REGRESS} --vectors no_newline.golden)
# 64 MiB and a byte, sparse.
execute_process(COMMAND truncate -s 67108865 ${WORK_DIR}/big.json RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "truncate -s failed: ${rc}")
endif()
run(merge_big 2 "fp24-regress: --merge: big.json: over 64 MiB, too large for a shard report"
    ${REGRESS} --merge big.json)
run(sweep_merge_big 2 "--merge: big.json: over 64 MiB, too large for a shard report" ${MC1} sweep --merge big.json)
file(REMOVE ${WORK_DIR}/big.json)

# ---- options that do not go together ----
foreach(option --long --exhaustive-pairs "--random;5" --no-structured "--seed;2")
  list(GET option 0 name)
  run(vectors_with${name} 2 "fp24-regress: (--vectors excludes ${name}|${name} excludes --vectors)" ${run} ${option})
endforeach()
foreach(k 1 2)
  run(shard${k} 0 "" ${run} --shard ${k}/2 --json s-${k}.json)
endforeach()
run(merge 0 "" ${REGRESS} --merge s-1.json s-2.json --json merged.json)
run(merge_with_vectors 2 "fp24-regress: --merge excludes --vectors" ${REGRESS} --merge s-1.json s-2.json --vectors g.golden)
run(merge_with_shard 2 "fp24-regress: --merge excludes --shard" ${REGRESS} --merge s-1.json s-2.json --shard 1/2)

# ---- shard reports the merge must not take on trust ----
file(READ ${WORK_DIR}/s-1.json s1)
file(READ ${WORK_DIR}/s-2.json s2)
string(JSON op0 GET "${s1}" ops 0 op)
# bad(NAME ERR-regex [SECOND] JSON-PATH... VALUE): s-1.json with the member at
# JSON-PATH set to VALUE (JSON text) merged with s-2.json (or, with SECOND,
# with s-2.json changed the same way).
function(bad name err_re)
  set(args ${ARGN})
  set(both FALSE)
  if(args MATCHES "^SECOND;")
    set(both TRUE)
    list(REMOVE_AT args 0)
  endif()
  string(JSON one SET "${s1}" ${args})
  file(WRITE ${WORK_DIR}/${name}-1.json "${one}")
  set(two s-2.json)
  if(both)
    string(JSON other SET "${s2}" ${args})
    file(WRITE ${WORK_DIR}/${name}-2.json "${other}")
    set(two ${name}-2.json)
  endif()
  run(${name} 2 "fp24-regress: --merge: ${name}-[12].json:[0-9]+: ${err_re}"
      ${REGRESS} --merge ${name}-1.json ${two} --json ${name}-merged.json)
  if(EXISTS ${WORK_DIR}/${name}-merged.json)
    message(SEND_ERROR "${name}: a merged report was written")
  endif()
endfunction()
string(JSON vectors GET "${s1}" ops 0 vectors)
string(JSON same SET "${s1}" ops 0 vectors ${vectors})  # CMake's own layout of the same report: merged
file(WRITE ${WORK_DIR}/relaid-1.json "${same}")
run(relaid 0 "" ${REGRESS} --merge relaid-1.json s-2.json --json relaid-merged.json)
bad(negative "\"vectors\" is -1, not a count" ops 0 vectors -1)
bad(fraction "\"vectors\" is 1.5, not a count" ops 0 vectors 1.5)
bad(count_64bit "\"rtl_vs_model\" is .*, not a count" ops 0 rtl_vs_model 18446744073709551615)
bad(sum_over_2_53 "\"vectors\" sums to over 2\\^53" SECOND ops 0 vectors 9007199254740992)
bad(count_text "\"vectors\" is string, not number" ops 0 vectors "\"12\"")
bad(unknown_op "unknown op \"fma\"" SECOND ops 0 op "\"fma\"")
bad(op_twice "op \"${op0}\" listed twice" SECOND ops 1 op "\"${op0}\"")
bad(shard_failed "\"passed\" is false, but nothing failed" passed false)
bad(passed_null "\"passed\" is null, but nothing failed" passed null)
bad(op_failed_passed "\"passed\" is true, but a check failed" ops 0 rtl_vs_model 3)
bad(op_passed_failed "\"passed\" is false, but nothing failed" ops 0 passed false)
