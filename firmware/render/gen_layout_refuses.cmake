# The generator refusing a layout file, judged by its exit status, its
# message and its output: gen_layout.cmake on IN exits non-zero, says
# EXPECT (a regular expression) on stderr, and writes no OUT.
#   cmake -DIN=<bad.inc> -DOUT=<out.hpp> -DEXPECT=<regex> -P gen_layout_refuses.cmake
file(REMOVE ${OUT})
execute_process(COMMAND ${CMAKE_COMMAND} -DIN=${IN} -DOUT=${OUT} -P ${CMAKE_CURRENT_LIST_DIR}/gen_layout.cmake
                RESULT_VARIABLE rc ERROR_VARIABLE err)
message(STATUS "gen_layout.cmake: exit status ${rc}\n${err}")
if(rc EQUAL 0)
  message(SEND_ERROR "gen_layout.cmake accepted ${IN} (exit status 0)")
endif()
if(NOT err MATCHES "${EXPECT}")
  message(SEND_ERROR "gen_layout.cmake's message does not say: ${EXPECT}")
endif()
if(EXISTS ${OUT})
  message(SEND_ERROR "gen_layout.cmake wrote ${OUT}")
endif()
