# CTest check of fp24-regress's report files (docs/reliability.md, output
# files): a report is written whole at the end or not at all, and when it
# cannot be, what was at its path (an older report, a directory) stays as it
# was and the exit status is 1, for a run's --text/--json and for --merge's;
# a report path that cannot be written is a usage error (2) found before the
# run, which leaves the other report's old file as it was. No device nodes:
# a write fails under `ulimit -f 0` (EFBIG, SIGXFSZ ignored) or on a directory.
#   cmake -DREGRESS=fp24-regress -DWORK_DIR=dir -P fp24_regress_outputs.cmake
include(${CMAKE_CURRENT_LIST_DIR}/fp24_cli_run.cmake)
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR})

# run(NAME RC ERR-regex ARGS...): fp24-regress ARGS in WORK_DIR.
function(run name want_rc err_re)
  run_in_work(${name} ${want_rc} "${err_re}" ${REGRESS} ${ARGN})
endfunction()

# run_no_space(NAME RC ERR-regex ARGS...): the same with regular files
# limited to 0 bytes, so that every write of a report fails.
function(run_no_space name want_rc err_re)
  execute_process(COMMAND sh -c "trap '' XFSZ; ulimit -f 0; exec \"$0\" \"$@\"" ${REGRESS} ${ARGN}
    WORKING_DIRECTORY ${WORK_DIR} OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE rc)
  if(NOT rc EQUAL want_rc OR NOT err MATCHES "${err_re}")
    message(SEND_ERROR "${name}: exit ${rc} (wanted ${want_rc})\nstdout: ${out}\nstderr: ${err}\n"
                       "wanted stderr ~ '${err_re}'")
  endif()
endfunction()

# old_reports(): old.txt and old.json, each holding "old NAME\n".
function(old_reports)
  file(WRITE ${WORK_DIR}/old.txt "old old.txt\n")
  file(WRITE ${WORK_DIR}/old.json "old old.json\n")
endfunction()

# expect_old(CASE FILE...): each FILE still there, holding "old FILE\n".
function(expect_old case)
  foreach(f ${ARGN})
    if(NOT EXISTS ${WORK_DIR}/${f})
      message(SEND_ERROR "${case}: ${f} was removed")
      continue()
    endif()
    file(READ ${WORK_DIR}/${f} text)
    if(NOT text STREQUAL "old ${f}\n")
      message(SEND_ERROR "${case}: ${f} changed: '${text}'")
    endif()
  endforeach()
endfunction()

file(WRITE ${WORK_DIR}/g.golden "neg 3f0000\nadd 3f0000 3f0000 400000 00\n")
set(run --vectors g.golden --threads 1)

# A report path that cannot be written fails before the run, and the other
# report's old file is not opened (it used to be left empty).
old_reports()
run(early_missing_dir 2 "nodir/x.json: cannot open for writing: .*No such file or directory"
    ${run} --text old.txt --json nodir/x.json)
expect_old(early_missing_dir old.txt)
file(MAKE_DIRECTORY ${WORK_DIR}/a_dir)
run(early_directory 2 "a_dir: cannot open for writing: is a directory" ${run} --json old.json --text a_dir)
expect_old(early_directory old.json)

# A report that cannot be written at the end: exit 1, the old files stay
# (they used to be emptied, then removed).
old_reports()
run_no_space(run_no_space 1 "fp24-regress: old.(txt|json): cannot write: File too large"
             ${run} --text old.txt --json old.json)
expect_old(run_no_space old.txt old.json)

# Written: both reports replaced whole.
run(run_writes 0 "" ${run} --text old.txt --json old.json)
file(READ ${WORK_DIR}/old.txt text)
file(READ ${WORK_DIR}/old.json json)
string(JSON schema ERROR_VARIABLE bad GET "${json}" schema)
if(NOT text MATCHES "^fp24-regress: g.golden, 2 vectors.*PASS\n$" OR NOT schema STREQUAL "fp24-regress/1")
  message(SEND_ERROR "run_writes: old.txt '${text}', old.json schema '${schema}' ${bad}")
endif()

# No report replaces an input or the other report (cmdline::Files), through
# symbolic and hard links: a usage error before the run, the input as it was.
file(READ ${WORK_DIR}/g.golden golden)
run(json_is_vectors 2 "--json g.golden would replace the vectors g.golden" ${run} --json g.golden)
run(text_is_vectors 2 "--text ./g.golden would replace the vectors g.golden" ${run} --text ./g.golden)
file(REMOVE ${WORK_DIR}/g-link.golden ${WORK_DIR}/g-hard.golden)
file(CREATE_LINK g.golden ${WORK_DIR}/g-link.golden SYMBOLIC)
file(CREATE_LINK ${WORK_DIR}/g.golden ${WORK_DIR}/g-hard.golden)
run(json_is_vectors_link 2 "--json g.golden would replace the vectors g-link.golden" --vectors g-link.golden --json g.golden)
run(text_is_vectors_hard_link 2 "--text g-hard.golden would replace the vectors g.golden" ${run} --text g-hard.golden)
run(text_is_json 2 "--text and --json name one file: r.json" ${run} --text r.json --json r.json)
file(READ ${WORK_DIR}/g.golden golden_after)
if(NOT golden_after STREQUAL golden)
  message(SEND_ERROR "an output replaced the vectors g.golden: '${golden_after}'")
endif()

# --merge: a report that cannot be written is found before the merge (exit
# 2) and leaves what was at its path (an empty directory used to be removed).
foreach(k 1 2)
  run(shard${k} 0 "" ${run} --shard ${k}/2 --json s-${k}.json)
endforeach()
# A merged report on a shard's report, directly or through a link.
file(READ ${WORK_DIR}/s-1.json shard1)
file(REMOVE ${WORK_DIR}/s-link.json)
file(CREATE_LINK s-1.json ${WORK_DIR}/s-link.json SYMBOLIC)
run(merge_json_is_report 2 "--json s-1.json would replace the report s-1.json" --merge s-1.json s-2.json --json s-1.json)
run(merge_text_is_report_link 2 "--text s-link.json would replace the report s-1.json"
    --merge s-1.json s-2.json --text s-link.json)
file(READ ${WORK_DIR}/s-1.json shard1_after)
if(NOT shard1_after STREQUAL shard1)
  message(SEND_ERROR "fp24-regress --merge replaced the shard's report s-1.json")
endif()
file(MAKE_DIRECTORY ${WORK_DIR}/merged_dir)
run(merge_directory 2 "fp24-regress: --json: merged_dir: cannot open for writing: is a directory"
    --merge s-1.json s-2.json --json merged_dir)
if(NOT IS_DIRECTORY ${WORK_DIR}/merged_dir)
  message(SEND_ERROR "merge_directory: the directory merged_dir was removed")
endif()
old_reports()
run_no_space(merge_no_space 1 "fp24-regress: old.json: cannot write: File too large"
             --merge s-1.json s-2.json --json old.json --text old.txt)
expect_old(merge_no_space old.json old.txt)
run(merge_missing_dir 2 "fp24-regress: --json: nodir/m.json: cannot open for writing: cannot create a temporary file beside it"
    --merge s-1.json s-2.json --json nodir/m.json)
# One report that cannot be written leaves the other unwritten too.
old_reports()
run(merge_one_fails 2 "fp24-regress: --text: nodir/m.txt: cannot open for writing"
    --merge s-1.json s-2.json --json old.json --text nodir/m.txt)
expect_old(merge_one_fails old.json old.txt)
run(merge_writes 0 "" --merge s-1.json s-2.json --json old.json --text old.txt)
file(READ ${WORK_DIR}/old.txt text)
if(NOT text MATCHES "merged 2 shards.*PASS\n$")
  message(SEND_ERROR "merge_writes: old.txt '${text}'")
endif()

# Nothing staged is left behind by any of these.
file(GLOB staged ${WORK_DIR}/.*.tmp.* ${WORK_DIR}/*/.*.tmp.*)
if(staged)
  message(SEND_ERROR "temporary files left: ${staged}")
endif()
