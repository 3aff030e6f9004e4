# The layout generator refusing a layout file, judged by its exit status, its
# message and its output: GENERATOR (firmware/render/gen_layout.cmake) on IN
# exits non-zero, says EXPECT (a regular expression) on stderr, and writes no OUT.
#   cmake -DGENERATOR=<gen_layout.cmake> -DIN=<bad.inc> -DOUT=<out.hpp> -DEXPECT=<regex> -P gen_layout_refuses.cmake
file(REMOVE ${OUT})
execute_process(COMMAND ${CMAKE_COMMAND} -DIN=${IN} -DOUT=${OUT} -P ${GENERATOR}
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
