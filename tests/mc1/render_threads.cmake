# --threads does not change a byte (docs/platform.md "Host threads"): the
# frame PNG, the statistics JSON without its host-time line and the Gantt
# SVG of `mc1 render` (ISS and RTL engines) and of `mc1 diag` are the same
# files for 1, 2 and 4 threads.
#   cmake -DMC1=<mc1> -DSCENE=<scene.json> -DOUT=<dir> -P render_threads.cmake
file(MAKE_DIRECTORY ${OUT})

function(run name)
  execute_process(COMMAND ${MC1} ${ARGN} --quiet --out ${OUT}/${name}.png --stats ${OUT}/${name}.json
                          --gantt ${OUT}/${name}.svg RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "mc1 ${ARGN}: exit status ${rc}")
  endif()
  # The APU engines' host time on the simulation's own thread: all of it on
  # one thread, at most all of it on more (the workers clock the rest).
  file(READ ${OUT}/${name}.json text)
  string(JSON all GET "${text}" host apu_engine_seconds)
  string(JSON sim GET "${text}" host apu_engine_seconds_simulation_thread)
  string(JSON threads GET "${text}" host threads)
  if(threads EQUAL 1 AND NOT sim STREQUAL all)
    message(FATAL_ERROR "mc1 ${ARGN}: one thread, but ${sim} s of the engines' ${all} s on the simulation's thread")
  elseif(NOT sim LESS_EQUAL all)
    message(FATAL_ERROR "mc1 ${ARGN}: ${sim} s on the simulation's thread, more than the engines' ${all} s")
  endif()
  # The host's seconds are the only figures that may differ.
  file(STRINGS ${OUT}/${name}.json lines)
  list(FILTER lines EXCLUDE REGEX "host")
  string(REPLACE ";" "\n" lines "${lines}")
  file(WRITE ${OUT}/${name}.sim.json "${lines}\n")
endfunction()

function(same a b)
  foreach(ext png sim.json svg)
    execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${OUT}/${a}.${ext} ${OUT}/${b}.${ext}
                    RESULT_VARIABLE diff)
    if(NOT diff EQUAL 0)
      message(FATAL_ERROR "${b}.${ext} differs from ${a}.${ext}")
    endif()
  endforeach()
  message(STATUS "${b}: PNG, statistics and chart the same as ${a}'s")
endfunction()

# name,command line (comma-separated)
set(cases
    "iss,render,${SCENE},--size,64x48,--nodes,16,--engine,iss"
    # 8x8 blocks: more data hand-overs, which a catch-up job may make (hw/nc)
    "iss-b8,render,${SCENE},--size,64x48,--nodes,8,--block,8,--engine,iss"
    "rtl,render,${SCENE},--size,48x32,--nodes,8,--engine,rtl"
    # the RTL engine's data hand-overs made by catch-up jobs too (untraced model)
    "rtl-b8,render,${SCENE},--size,32x24,--nodes,4,--block,8,--engine,rtl"
    # the RTL core on NC 3, the ISS on the others
    "mixed,render,${SCENE},--size,48x32,--nodes,8,--rtl-nodes,3"
    "diag,diag,--size,64x64,--nodes,16,--block,8")
foreach(c ${cases})
  string(REPLACE "," ";" parts "${c}")
  list(GET parts 0 name)
  list(REMOVE_AT parts 0)
  foreach(t 1 2 4)
    run(${name}-t${t} ${parts} --threads ${t})
  endforeach()
  same(${name}-t1 ${name}-t2)
  same(${name}-t1 ${name}-t4)
endforeach()
