# CTest check: each kind of malformed input makes `fp24-run` exit non-zero,
# print nothing on stdout, and name the line (and the offending token) on
# stderr as `<stdin>:LINE: ...`.
#   cmake -DPROGRAM=... -DWORK_DIR=... -P fp24_run_errors.cmake
set(failures 0)

function(expect_error name input pattern)
  set(file ${WORK_DIR}/${name}.vec)
  file(WRITE ${file} "${input}")
  execute_process(COMMAND ${PROGRAM} --engine model
    INPUT_FILE ${file} OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE rc)
  if(rc EQUAL 0 OR NOT out STREQUAL "" OR NOT err MATCHES "${pattern}")
    message(SEND_ERROR "case ${name}: exit ${rc}, stdout '${out}', stderr '${err}'; wanted non-zero exit and stderr matching '${pattern}'")
  endif()
endfunction()

set(ok "add 3f0000 3f0000\n# a comment\n\n")
expect_error(unknown_op      "${ok}fma 1 2\n"            "^<stdin>:4: unknown op 'fma'")
expect_error(upper_case_op   "${ok}ADD 1 2\n"            "^<stdin>:4: unknown op 'ADD'")
expect_error(missing_operand "${ok}mul 3f0000\n"         "^<stdin>:4: mul needs 2 operand")
expect_error(extra_operand   "${ok}sqrt 3f0000 1\n"      "^<stdin>:4: extra operand '1' after sqrt")
expect_error(not_hex         "${ok}add 3f0000 3g0000\n"  "^<stdin>:4: operand '3g0000' is not hex")
expect_error(hex_prefix      "${ok}neg 0x3f0000\n"       "^<stdin>:4: operand '0x3f0000' is not hex")
expect_error(too_wide        "${ok}abs 1000000\n"        "^<stdin>:4: operand '1000000' is out of range")
expect_error(float_too_wide  "${ok}float 10000\n"        "^<stdin>:4: operand '10000' is out of range \\(max ffff\\)")
expect_error(negative        "${ok}fix -1\n"             "^<stdin>:4: operand '-1' is not hex")
expect_error(first_line      "cos\n"                     "^<stdin>:1: cos needs 1 operand")
expect_error(trailing_comment "${ok}neg 1 # x\n"         "^<stdin>:4: extra operand '#' after neg")

# Command-line errors: "fp24-run: ..." on stderr, exit 2 (more in tests/cli_test.cmake).
execute_process(COMMAND ${PROGRAM} --engine fpga INPUT_FILE ${WORK_DIR}/unknown_op.vec
  ERROR_VARIABLE err RESULT_VARIABLE rc)
if(NOT rc EQUAL 2 OR NOT err MATCHES "^fp24-run: --engine: fpga not in {model,rtl,oracle,all}")
  message(SEND_ERROR "case bad_engine: exit ${rc}, stderr '${err}'")
endif()
execute_process(COMMAND ${PROGRAM} --engine model --trace x.fst INPUT_FILE ${WORK_DIR}/unknown_op.vec
  ERROR_VARIABLE err RESULT_VARIABLE rc)
if(NOT rc EQUAL 2 OR NOT err MATCHES "^fp24-run: --trace needs --engine rtl")
  message(SEND_ERROR "case trace_without_rtl: exit ${rc}, stderr '${err}'")
endif()
