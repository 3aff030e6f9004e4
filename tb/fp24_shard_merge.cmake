# CTest check of fp24-regress --shard and --merge (docs/fp24-verification.md,
# "Sharded runs"): the unsharded run (1/1) and the merge of its 3 shards
# report the same counts, for a run of built-in sets (exhaustive one-operand
# ops, random pairs) and for a --vectors file with planted wrong expected
# results (nonzero mismatch totals, SIN's ulp maximum); bad shards and bad
# merges are usage errors that name the report.
#   cmake -DREGRESS=fp24-regress -DWORK_DIR=dir -P fp24_shard_merge.cmake
include(${CMAKE_CURRENT_LIST_DIR}/fp24_report_compare.cmake)
include(${CMAKE_CURRENT_LIST_DIR}/fp24_cli_run.cmake)
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR})

# run(NAME RC ERR-regex ARGS...)
function(run name want_rc err_re)
  run_in_work(${name} ${want_rc} "${err_re}" ${REGRESS} ${ARGN})
endfunction()

# sharded(NAME RC ARGS...): ARGS unsharded and as 3 shards, merged, compared.
function(sharded name want_rc)
  run(${name}_whole ${want_rc} "" ${ARGN} --shard 1/1 --json ${name}.json)
  set(parts "")
  foreach(k 1 2 3)
    run(${name}_shard${k} ${want_rc} "" ${ARGN} --shard ${k}/3 --json ${name}-${k}.json)
    list(PREPEND parts ${name}-${k}.json)  # in any order
  endforeach()
  run(${name}_merge ${want_rc} "" --merge ${parts} --json ${name}-merged.json)
  fp24_report_compare(${WORK_DIR}/${name}.json ${WORK_DIR}/${name}-merged.json)
  file(READ ${WORK_DIR}/${name}-merged.json merged)
  string(JSON shard GET "${merged}" shard)
  if(NOT shard STREQUAL "all/3")
    message(SEND_ERROR "${name}: merged report's shard '${shard}', not all/3")
  endif()
endfunction()

set(quick --ops float,neg,add,cmp --no-structured --random 100000 --threads 2)
sharded(builtin 0 ${quick})
file(READ ${WORK_DIR}/builtin-merged.json merged)
string(JSON neg GET "${merged}" ops 1 vectors)
string(JSON add GET "${merged}" ops 2 vectors)
if(NOT neg EQUAL 16777216 OR NOT add EQUAL 100000)
  message(SEND_ERROR "builtin: merged vectors neg ${neg} add ${add}, not 16777216 and 100000")
endif()

# 600 SIN operands and 90 ADD golden lines, every third one wrong (the
# expected result of 1 + 1 for a pseudo-random pair).
string(RANDOM LENGTH 6 ALPHABET 0123456789abcdef RANDOM_SEED 16 x)
set(text "")
foreach(i RANGE 1 600)
  string(RANDOM LENGTH 6 ALPHABET 0123456789abcdef x)
  string(APPEND text "sin ${x}\n")
endforeach()
foreach(i RANGE 1 30)
  string(RANDOM LENGTH 5 ALPHABET 0123456789abcdef x)
  string(RANDOM LENGTH 5 ALPHABET 0123456789abcdef y)
  string(APPEND text "add 3f0000 3f0000 400000 00\nadd 5${x} 5${y} 400000 00\nadd 3f8000 3f8000 408000 00\n")
endforeach()
file(WRITE ${WORK_DIR}/planted.golden "${text}")
sharded(planted 1 --vectors planted.golden --show 3 --threads 2)
file(READ ${WORK_DIR}/planted-merged.json merged)
string(JSON golden GET "${merged}" ops 0 model_vs_golden)
string(JSON ulp GET "${merged}" ops 1 max_ulp_error)
string(JSON failures LENGTH "${merged}" ops 0 failures)
if(NOT golden EQUAL 30 OR NOT ulp GREATER 0.25 OR NOT ulp LESS 1 OR NOT failures EQUAL 3)
  message(SEND_ERROR "planted: merged golden mismatches ${golden} (wanted 30), SIN max ulp ${ulp}, "
                     "${failures} failures listed (wanted 3 = --show)")
endif()

set(tiny --ops neg --no-rtl --no-oracle)
foreach(bad 0/3 4/3 3 1/0 a/b 1/3x 1/4294967296)
  run(shard_${bad} 2 "--shard: '${bad}' is not K/N" ${tiny} --shard ${bad})
endforeach()
run(missing 2 "--merge: shard 2/3 missing" --merge builtin-1.json builtin-3.json)
run(twice 2 "--merge: builtin-1.json: shard 1 given twice" --merge builtin-1.json builtin-1.json builtin-3.json)
run(other_run 2 "--merge: planted-2.json: \"vectors_file\" differs from builtin-1.json's: not the same run"
    --merge builtin-1.json planted-2.json builtin-3.json)
# A shard that holds none of an op's vectors (its counts zeroed, as a shard
# cut short would leave them): the shards no longer add up to the run's set,
# and the merge fails (exit 1) naming the op, even with every count passing.
foreach(k 1 2 3)
  file(READ ${WORK_DIR}/builtin-${k}.json text)
  string(REGEX REPLACE "\"op\": \"neg\", \"vectors\": [0-9]+" "\"op\": \"neg\", \"vectors\": 0" text "${text}")
  file(WRITE ${WORK_DIR}/zero-${k}.json "${text}")
endforeach()
run(zero_vectors 1 "neg: the shards hold 0 of the run's 16777216 vectors" --merge zero-1.json zero-2.json zero-3.json)
file(READ ${WORK_DIR}/builtin-2.json text)
string(REGEX REPLACE "\"set_vectors\": 16777216" "\"set_vectors\": 65536" text "${text}")
file(WRITE ${WORK_DIR}/other-set.json "${text}")
run(other_set 2 "other-set.json:[0-9]+: \"set_vectors\" differs from builtin-1.json's: not the same run"
    --merge builtin-1.json other-set.json builtin-3.json)
run(merged_again 2 "builtin-merged.json:10: shard 'all/3' is not K/N" --merge builtin-merged.json)
file(WRITE ${WORK_DIR}/other.json "{\"schema\": \"mc1-stats/1\"}\n")
run(schema 2 "other.json:1: schema 'mc1-stats/1', not fp24-regress/1" --merge other.json)
file(WRITE ${WORK_DIR}/broken.json "{\"schema\": \n")
run(syntax 2 "broken.json:" --merge broken.json)
