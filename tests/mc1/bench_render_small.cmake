# mc1 bench-render's parts on a small frame (tiny.json, 16x16, on 2 NCs, --rtl,
# --repeat 2), its verdict from its exit status and the figures of its
# --json report, not from its printout: exit status 0; "frames_equal" true
# (every run's frame the same, the RTL engine's too); the runs in order (the
# speedup run, the static split, the compared frame's runs:
# the speedup run counts as the first ISS one, so one more "lpt", two "RTL
# engine", two "RTL core on NC 1" with rtl_nodes [1]), each with a positive
# simulated time, host time and CPU time; the same simulated time for every run of
# the compared frame (lpt on 2 NCs) whatever the engine; positive host-time
# ratios (no speed asserted).
#   cmake -DMC1=<mc1> -DSCENE=<tiny.json> -DWORK_DIR=<dir> -P bench_render_small.cmake
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR})
set(report ${WORK_DIR}/bench.json)
execute_process(COMMAND ${MC1} bench-render --scene ${SCENE} --size 16x16 --nodes 2 --static-nodes 2 --big 0 --rtl
                        --repeat 2 --json ${report}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message(STATUS "${out}${err}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "mc1 bench-render: exit status ${rc} (0 wanted)")
endif()
file(READ ${report} json)

string(JSON equal GET "${json}" frames_equal)
if(NOT equal STREQUAL "ON")
  message(SEND_ERROR "frames_equal: ${equal} (true wanted): frames of one size differ between runs")
endif()

# label nodes engine rtl_nodes, per run in order
set(want "speedup 2 iss 0" "static split 2 iss 0" "lpt 2 iss 0" "RTL engine 2 rtl 0"
         "RTL engine 2 rtl 0" "RTL core on NC 1 2 iss 1" "RTL core on NC 1 2 iss 1")
list(LENGTH want n_want)
string(JSON n_runs LENGTH "${json}" runs)
if(NOT n_runs EQUAL n_want)
  message(FATAL_ERROR "runs: ${n_runs} (${n_want} wanted)")
endif()
set(compared_time "")
math(EXPR last "${n_runs} - 1")
foreach(i RANGE ${last})
  string(JSON label GET "${json}" runs ${i} label)
  string(JSON nodes GET "${json}" runs ${i} nodes)
  string(JSON engine GET "${json}" runs ${i} engine)
  string(JSON rtl_nodes LENGTH "${json}" runs ${i} rtl_nodes)
  string(JSON sim GET "${json}" runs ${i} simulated_time_s)
  string(JSON host GET "${json}" runs ${i} host_seconds)
  string(JSON cpu GET "${json}" runs ${i} host_cpu_seconds)
  list(GET want ${i} w)
  if(NOT "${label} ${nodes} ${engine} ${rtl_nodes}" STREQUAL w)
    message(SEND_ERROR "run ${i}: ${label} ${nodes} ${engine} rtl_nodes ${rtl_nodes} (${w} wanted)")
  endif()
  if(NOT sim GREATER 0 OR NOT host GREATER 0 OR NOT cpu GREATER 0)
    message(SEND_ERROR "run ${i} (${label}): simulated ${sim} s, host ${host} s, CPU ${cpu} s (all > 0 wanted)")
  endif()
  if(NOT label STREQUAL "static split")  # the compared frame: lpt on 2 NCs
    if(compared_time STREQUAL "")
      set(compared_time ${sim})
    elseif(NOT sim STREQUAL compared_time)
      message(SEND_ERROR "run ${i} (${label}): simulated ${sim} s, the compared frame's first run ${compared_time} s")
    endif()
  endif()
endforeach()

foreach(key cosim_over_reference cosim_over_reference_cpu rtl_over_iss rtl_over_iss_cpu rtl_nc1_over_iss
            rtl_nc1_over_iss_cpu lpt_over_static cosim_cpu_seconds reference_cpu_seconds rtl_cpu_seconds)
  string(JSON v GET "${json}" ${key})
  if(NOT v GREATER 0)
    message(SEND_ERROR "${key}: ${v} (> 0 wanted)")
  endif()
endforeach()
string(JSON repeat GET "${json}" repeat)
if(NOT repeat EQUAL 2)
  message(SEND_ERROR "repeat: ${repeat} (2 wanted)")
endif()
