# ctest install_consumer (docs/library.md): `cmake --install` of the build
# into WORK/prefix, then as a user would: examples/ configured and built with
# find_package(MC1) and run (the FP24 golden vectors, the SystemC bench); a
# program built from `pkg-config --cflags --libs mc1` alone; the Python
# golden-vector check with PYTHONPATH pointing into the prefix. Every step's
# failure fails the test, naming the step.
function(step name)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  message(STATUS "${name}:\n${out}${err}")
  if(rc)
    message(FATAL_ERROR "install_consumer: ${name} failed (${rc})")
  endif()
endfunction()

set(prefix ${WORK}/prefix)
file(REMOVE_RECURSE ${WORK})
step("cmake --install" ${CMAKE_COMMAND} --install ${BUILD} --prefix ${prefix})
foreach(f ${LIBDIR}/cmake/MC1/MC1Config.cmake ${LIBDIR}/pkgconfig/mc1.pc include/mc1/apu_tlm.hpp
          include/mc1/apu_isa.hpp bin/mc1 bin/apuasm share/mc1/kernels/shade.apu share/mc1/kernels/shade.bin
          share/mc1/gtkw/apu-core.gtkw share/doc/mc1/library.md)
  if(NOT EXISTS ${prefix}/${f})
    message(FATAL_ERROR "install_consumer: ${prefix}/${f} was not installed")
  endif()
endforeach()

# The installed mc1 finds its default scene in the installed data (share/mc1),
# not in the source tree it was built from.
execute_process(COMMAND ${prefix}/bin/mc1 bench-render --help RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
string(FIND "${out}" "(default: ${prefix}/share/mc1/scenes/whitted.json)" at)
if(rc OR at EQUAL -1)
  message(FATAL_ERROR "install_consumer: the installed mc1 bench-render's default scene is not "
          "${prefix}/share/mc1/scenes/whitted.json:\n${out}${err}")
endif()

set(launcher)
if(LAUNCHER)
  set(launcher -DCMAKE_CXX_COMPILER_LAUNCHER=${LAUNCHER})
endif()
step("configure examples" ${CMAKE_COMMAND} -S ${SRC}/examples -B ${WORK}/examples -DCMAKE_PREFIX_PATH=${prefix}
     -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER=${CXX} ${launcher})
step("build examples" ${CMAKE_COMMAND} --build ${WORK}/examples -j2)
step("run examples" ${CMAKE_CTEST_COMMAND} --test-dir ${WORK}/examples --output-on-failure)

find_program(PKG_CONFIG pkg-config REQUIRED)
set(ENV{PKG_CONFIG_PATH} ${prefix}/${LIBDIR}/pkgconfig)
execute_process(COMMAND ${PKG_CONFIG} --cflags --libs mc1 RESULT_VARIABLE rc OUTPUT_VARIABLE flags
                ERROR_VARIABLE err OUTPUT_STRIP_TRAILING_WHITESPACE)
if(rc)
  message(FATAL_ERROR "install_consumer: pkg-config mc1 failed: ${err}")
endif()
separate_arguments(flags UNIX_COMMAND "${flags}")
step("pkg-config build" ${LAUNCHER} ${CXX} -O1 ${SRC}/examples/fp24_pkgconfig.cpp ${flags} -o ${WORK}/fp24_pkgconfig)
step("pkg-config run" ${WORK}/fp24_pkgconfig)

step("python golden vectors" ${CMAKE_COMMAND} -E env PYTHONPATH=${prefix}/${PYDIR}
     ${PYTHON} ${SRC}/examples/fp24_known.py ${prefix}/share/mc1/vectors/fp24_known.vec
     ${prefix}/share/mc1/vectors/fp24_known.expected)
