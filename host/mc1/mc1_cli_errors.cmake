# CTest check of `mc1`'s exit codes and outputs (docs/reliability.md):
# 2 for bad input naming it, 1 for a failed write with nothing left behind,
# --help and --version 0.
#   cmake -DMC1=... -DSCENES=... -DWORK_DIR=... -P mc1_cli_errors.cmake
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR})

# expect(NAME RC PATTERN ARGS...): exit RC, stderr (or stdout for 0) matching PATTERN.
function(expect name want pattern)
  execute_process(COMMAND ${MC1} ${ARGN} OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE rc)
  if(NOT rc EQUAL want OR NOT "${out}${err}" MATCHES "${pattern}")
    message(SEND_ERROR "case ${name}: exit ${rc} (wanted ${want}), output '${out}${err}' (wanted '${pattern}')")
  endif()
endfunction()

set(tiny ${SCENES}/tiny.json --size 16x16 --nodes 2 --quiet)
expect(version 0 "^mc1 \\(MC-1 virtual platform\\) [0-9]+\\.[0-9]+\\.[0-9]+" --version)
expect(help 0 "usage: mc1" --help)
expect(help_command 0 "usage: mc1 \\[OPTIONS\\] SUBCOMMAND" help)
expect(render_help 0 "usage: mc1 render.*--kill-node K@TIME" render --help)
expect(no_command 2 "mc1: A subcommand is required" )
expect(unknown_command 2 "mc1: unknown command 'paint'" paint)
expect(missing_scene 2 "mc1 render: ${WORK_DIR}/none.json: cannot open scene file" render ${WORK_DIR}/none.json)
expect(scene_is_dir 2 "is a directory" render ${WORK_DIR})
expect(params_is_dir 2 "is a directory \\(expected a parameter file\\)" render ${tiny} --params ${WORK_DIR})
expect(bad_kernel 2 "--kernel: ${WORK_DIR}: is a directory" diag --nodes 2 --kernel ${WORK_DIR})
expect(bad_option 2 "not expected: --bogus" render ${tiny} --bogus)
expect(bad_number 2 "mc1 diag: --nodes: '0' is out of range \\[1, 4096\\]" diag --nodes 0)
expect(bad_time 2 "--kill-node: bad time '20parsecs'" render ${tiny} --kill-node 1@20parsecs)
expect(params_extra 2 "not expected: extra" params extra)
expect(window_needs_trace 2 "--trace-from and --trace-to need --trace" render ${tiny} --trace-from 1ms)
expect(window_empty 2 "--trace-to must be later than --trace-from" render ${tiny} --trace t.fst --trace-from 2ms --trace-to 1ms)
expect(window_bad_time 2 "--trace-to: bad time" render ${tiny} --trace t.fst --trace-to soon)
expect(rtl_nodes_range 2 "--rtl-nodes: '3' is out of range \\[1, 2\\]" render ${tiny} --rtl-nodes 1,3)
expect(rtl_nodes_twice 2 "--rtl-nodes: NC 2 is given twice" render ${tiny} --rtl-nodes 2,1,2)
expect(rtl_nodes_bad 2 "--rtl-nodes: 'x' is not a number" render ${tiny} --rtl-nodes 2,x)
expect(rtl_nodes_all_rtl 2 "--rtl-nodes: with --engine rtl every NC runs the RTL core" render ${tiny} --engine rtl --rtl-nodes 1)

# --params and --param apply in the order given, as one sequence.
file(WRITE ${WORK_DIR}/w4.params "hdlc_window = 4\n")
expect(params_file_last 0 "hdlc_window = 4 " params --param hdlc_window=3 --params ${WORK_DIR}/w4.params)
expect(param_last 0 "hdlc_window = 6 " params --params=${WORK_DIR}/w4.params --param=hdlc_window=6)

# A failed write: exit 1, and none of the run's outputs is left behind.
expect(stats_full 1 "/dev/full: .*No space left on device" render ${tiny}
       --out ${WORK_DIR}/a.png --gantt ${WORK_DIR}/a.svg --stats /dev/full)
foreach(f a.png a.svg)
  if(EXISTS ${WORK_DIR}/${f})
    message(SEND_ERROR "case stats_full: ${f} was left behind")
  endif()
endforeach()
expect(out_full 1 "/dev/full: .*No space left on device" diag --nodes 2 --stats ${WORK_DIR}/d.json --out /dev/full)
if(EXISTS ${WORK_DIR}/d.json)
  message(SEND_ERROR "case out_full: d.json was left behind")
endif()
file(GLOB leftovers ${WORK_DIR}/.*)
if(leftovers)
  message(SEND_ERROR "temporary files left behind: ${leftovers}")
endif()

# All outputs written: each present.
expect(good 0 "" render ${tiny} --out ${WORK_DIR}/g.png --stats ${WORK_DIR}/g.json --gantt ${WORK_DIR}/g.svg)
foreach(f g.png g.json g.svg)
  if(NOT EXISTS ${WORK_DIR}/${f})
    message(SEND_ERROR "case good: ${f} missing")
  endif()
endforeach()
