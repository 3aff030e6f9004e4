# The fp24-regress test scripts' check of one command (fp24_shard_merge,
# fp24_regress_outputs, fp24_regress_inputs), included by each:
# run_in_work(NAME RC ERR-regex COMMAND ARGS...) runs COMMAND in WORK_DIR and
# fails the test unless it exits RC with stderr matching ERR-regex.
function(run_in_work name want_rc err_re)
  execute_process(COMMAND ${ARGN} WORKING_DIRECTORY ${WORK_DIR}
    OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE rc)
  if(NOT rc EQUAL want_rc OR NOT err MATCHES "${err_re}")
    message(SEND_ERROR "${name}: exit ${rc} (wanted ${want_rc})\nstdout: ${out}\nstderr: ${err}\n"
                       "wanted stderr ~ '${err_re}'")
  endif()
endfunction()
