# CTest check: `fp24-run --engine ENGINE < INPUT` must exit 0 and print
# exactly EXPECTED.
#   cmake -DPROGRAM=... -DENGINE=... -DINPUT=... -DEXPECTED=... -P fp24_run_vectors.cmake
execute_process(COMMAND ${PROGRAM} --engine ${ENGINE}
  INPUT_FILE ${INPUT} OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "fp24-run --engine ${ENGINE} < ${INPUT}: exit ${rc}\n${err}")
endif()
file(READ ${EXPECTED} want)
if(NOT out STREQUAL want)
  message(FATAL_ERROR "fp24-run --engine ${ENGINE} < ${INPUT}: output differs from ${EXPECTED}\n"
                      "got:\n${out}\nexpected:\n${want}")
endif()
