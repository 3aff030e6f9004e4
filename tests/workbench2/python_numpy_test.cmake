# The module mc1 without numpy (issue 43 item 6): `import mc1` must fail at
# once with an ImportError that names numpy, the interpreter the build is for
# and what to do; not succeed and fail at the first call with a bare
# "No module named 'numpy'". Two ways to hide numpy: `python3 -S` (no site, so
# no dist-packages on sys.path) and a sitecustomize that refuses numpy.
#   cmake -DPYTHON=... -DPYDIR=build/python -DWORK=dir -P python_numpy_test.cmake
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK}/block)
file(WRITE ${WORK}/block/sitecustomize.py [=[
import sys
class _NoNumpy:
    def find_spec(self, name, path=None, target=None):
        if name == "numpy" or name.startswith("numpy."):
            raise ImportError("No module named 'numpy' (hidden by the test's sitecustomize)")
        return None
sys.meta_path.insert(0, _NoNumpy())
]=])
file(STRINGS ${PYDIR}/mc1/_build.py built_for REGEX "^PYTHON = ")
string(REGEX REPLACE "^PYTHON = \"(.*)\"$" "\\1" built_for "${built_for}")
if(NOT built_for STREQUAL PYTHON)
  message(FATAL_ERROR "mc1/_build.py names ${built_for}, the build's Python is ${PYTHON}")
endif()

function(expect_refused name)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(rc EQUAL 0)
    message(FATAL_ERROR "${name}: import mc1 succeeded without numpy:\n${out}${err}")
  endif()
  foreach(want "ImportError: mc1: numpy cannot be imported" "No module named 'numpy'"
               "This build of mc1 is for ${PYTHON} \\(Python [0-9]+\\.[0-9]+\\)" "give it numpy")
    if(NOT err MATCHES "${want}")
      message(FATAL_ERROR "${name}: the error does not say '${want}':\n${err}")
    endif()
  endforeach()
  message(STATUS "${name}: ${err}")
endfunction()

expect_refused(no_site ${CMAKE_COMMAND} -E env PYTHONPATH=${PYDIR} ${PYTHON} -S -c "import mc1")
expect_refused(sitecustomize ${CMAKE_COMMAND} -E env PYTHONPATH=${WORK}/block:${PYDIR} ${PYTHON} -c "import mc1")

# With numpy the same import works, and a call on arrays too.
execute_process(COMMAND ${CMAKE_COMMAND} -E env PYTHONPATH=${PYDIR} ${PYTHON} -c
                        "import mc1; print(hex(int(mc1.fp24.from_float([1.5])[0])))"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT out MATCHES "^0x3f8000")
  message(FATAL_ERROR "with numpy: exit ${rc}, want 0x3f8000:\n${out}${err}")
endif()

# Another interpreter than the build's: the package copied with another
# recorded interpreter stands for it (the message is the same either way).
file(COPY ${PYDIR}/mc1 DESTINATION ${WORK}/other)
file(WRITE ${WORK}/other/mc1/_build.py "PYTHON = \"/opt/elsewhere/bin/python3\"\nPYTHON_VERSION = \"3.99\"\n")
execute_process(COMMAND ${CMAKE_COMMAND} -E env PYTHONPATH=${WORK}/other ${PYTHON} -S -c "import mc1"
                RESULT_VARIABLE rc ERROR_VARIABLE err)
if(rc EQUAL 0 OR NOT err MATCHES "for /opt/elsewhere/bin/python3 \\(Python 3.99\\)"
   OR NOT err MATCHES "-DPython3_EXECUTABLE=")
  message(FATAL_ERROR "another interpreter: the error does not name the build's and -DPython3_EXECUTABLE:\n${err}")
endif()
