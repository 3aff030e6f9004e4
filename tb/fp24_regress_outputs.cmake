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

# --merge: a report that cannot be written is exit 1 and leaves what was at
# its path (an empty directory used to be removed).
foreach(k 1 2)
  run(shard${k} 0 "" ${run} --shard ${k}/2 --json s-${k}.json)
endforeach()
file(MAKE_DIRECTORY ${WORK_DIR}/merged_dir)
run(merge_directory 1 "fp24-regress: merged_dir: is a directory" --merge s-1.json s-2.json --json merged_dir)
if(NOT IS_DIRECTORY ${WORK_DIR}/merged_dir)
  message(SEND_ERROR "merge_directory: the directory merged_dir was removed")
endif()
old_reports()
run_no_space(merge_no_space 1 "fp24-regress: old.json: cannot write: File too large"
             --merge s-1.json s-2.json --json old.json --text old.txt)
expect_old(merge_no_space old.json old.txt)
run(merge_missing_dir 1 "fp24-regress: nodir/m.json: cannot create a temporary file beside it"
    --merge s-1.json s-2.json --json nodir/m.json)
# One report that cannot be written leaves the other unwritten too.
old_reports()
run(merge_one_fails 1 "fp24-regress: nodir/m.txt: cannot create a temporary file beside it"
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
