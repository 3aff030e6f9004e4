# CTest check of `mc1`'s exit codes and outputs (docs/reliability.md):
# 2 for bad input naming it, 1 for a failed write with nothing left behind,
# --help and --version 0.
#   cmake -DMC1=... -DSCENES=... -DWORK_DIR=... -P mc1_cli_errors.cmake
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR})

# expect(NAME RC PATTERN ARGS...): exit RC, stderr (or stdout for 0) matching PATTERN.
function(expect name want pattern)
  execute_process(COMMAND ${MC1} ${ARGN} OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE rc)
  set(last_output "${out}${err}" PARENT_SCOPE)
  if(NOT rc EQUAL want OR NOT "${out}${err}" MATCHES "${pattern}")
    message(SEND_ERROR "case ${name}: exit ${rc} (wanted ${want}), output '${out}${err}' (wanted '${pattern}')")
  endif()
endfunction()

set(tiny ${SCENES}/tiny.json --size 16x16 --nodes 2 --quiet)
expect(version 0 "^mc1 \\(MC-1 virtual platform\\) [0-9]+\\.[0-9]+\\.[0-9]+" --version)
expect(help 0 "usage: mc1" --help)
expect(help_command 0 "usage: mc1 \\[OPTIONS\\] SUBCOMMAND" help)
expect(help_of_command 0 "^render a scene.*--kill-node K@TIME" help render)
expect(help_of_unknown 2 "mc1 help: unknown command 'paint'" help paint)
expect(render_help 0 "usage: mc1 render.*--kill-node K@TIME" render --help)
expect(no_command 2 "mc1: A subcommand is required" )
expect(unknown_command 2 "mc1: unknown command 'paint'" paint)
expect(missing_scene 2 "mc1 render: ${WORK_DIR}/none.json: cannot open scene file" render ${WORK_DIR}/none.json)
expect(scene_is_dir 2 "is a directory" render ${WORK_DIR})
expect(params_is_dir 2 "is a directory \\(expected a parameter file\\)" render ${tiny} --params ${WORK_DIR})
expect(bad_kernel 2 "--kernel: ${WORK_DIR}: is a directory" diag --nodes 2 --kernel ${WORK_DIR})
expect(bad_option 2 "not expected: --bogus" render ${tiny} --bogus)
expect(scene_twice 2 "SCENE and --scene are both given" render ${tiny} --scene ${SCENES}/room.json)
expect(list_json 2 "mc1 sweep: --list runs nothing: --json would write nothing" sweep --list --json ${WORK_DIR}/l.json)
expect(bad_number 2 "mc1 diag: --nodes: '0' is out of range \\[1, 4096\\]" diag --nodes 0)
expect(bad_size 2 "--size: bad size '16x16x16' \\(expected WxH" render ${SCENES}/tiny.json --size 16x16x16)
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
# Outputs that would replace an input or one another, and waveform paths
# their writers cannot take: exit 2 before the run, nothing written.
file(COPY ${SCENES}/tiny.json DESTINATION ${WORK_DIR})
file(READ ${WORK_DIR}/tiny.json scene_before)
expect(out_is_scene 2 "--out ${WORK_DIR}/tiny.json would replace the scene ${WORK_DIR}/tiny.json"
       render ${WORK_DIR}/tiny.json --size 16x16 --nodes 2 --quiet --out ${WORK_DIR}/tiny.json)
file(READ ${WORK_DIR}/tiny.json scene_after)
if(NOT scene_after STREQUAL scene_before)
  message(SEND_ERROR "case out_is_scene: the scene was replaced")
endif()
expect(out_is_stats 2 "--out and --stats name one file: ${WORK_DIR}/\\./x\\.png"
       render ${tiny} --out ${WORK_DIR}/x.png --stats ${WORK_DIR}/./x.png)
expect(gantt_is_params 2 "--gantt ${WORK_DIR}/w4.params would replace the timing table"
       render ${tiny} --params ${WORK_DIR}/w4.params --gantt ${WORK_DIR}/w4.params)
expect(vcd_is_stats 2 "mc1 diag: --stats and --vcd name one file" diag --nodes 2 --vcd ${WORK_DIR}/d.vcd
       --stats ${WORK_DIR}/d.vcd)
expect(trace_is_dir 2 "--trace: ${WORK_DIR}: cannot open for writing: is a directory" render ${tiny} --trace ${WORK_DIR})
expect(vcd_is_device 2 "--vcd: /dev/null: is not a regular file" render ${tiny} --vcd /dev/null)
expect(trace_no_dir 2 "--trace: ${WORK_DIR}/none/t.fst: cannot open for writing: cannot create a temporary file beside it"
       render ${tiny} --trace ${WORK_DIR}/none/t.fst)
foreach(f x.png d.vcd)
  if(EXISTS ${WORK_DIR}/${f})
    message(SEND_ERROR "an output of a refused command was written: ${f}")
  endif()
endforeach()
# A frame that cannot complete: exit 1, and the waveforms its writers began
# are gone, as the other outputs.
expect(failed_run_waveforms 1 "mc1 render: mc1\\.rc: the frame cannot complete: [^\n]* \\(at [0-9]+ ns\\)\n"
       render ${tiny} --kill-node 1@1ms --kill-node 2@1ms --vcd ${WORK_DIR}/k.vcd --trace ${WORK_DIR}/k.fst)
if(last_output MATCHES "In file:|In process:")
  message(SEND_ERROR "case failed_run_waveforms: SystemC's report decorations in the message: ${last_output}")
endif()
foreach(f k.vcd k.fst k.fst.gtkw)
  if(EXISTS ${WORK_DIR}/${f})
    message(SEND_ERROR "case failed_run_waveforms: ${f} was left behind")
  endif()
endforeach()
# A VCD is written where --vcd says, ".vcd" or not.
expect(vcd_name 0 "" render ${tiny} --vcd ${WORK_DIR}/plain)
if(NOT EXISTS ${WORK_DIR}/plain OR EXISTS ${WORK_DIR}/plain.vcd)
  message(SEND_ERROR "case vcd_name: --vcd plain did not write the file plain")
endif()

# An output path that cannot be written is found before the run (the frame
# would take its whole time first), with nothing left behind.
expect(out_no_dir 2 "--out: ${WORK_DIR}/none/x.png: cannot open for writing: cannot create a temporary file"
       render ${SCENES}/whitted.json --size 320x240 --quiet --out ${WORK_DIR}/none/x.png)
expect(stats_is_dir 2 "mc1 diag: --stats: ${WORK_DIR}: cannot open for writing: is a directory"
       diag --nodes 2 --stats ${WORK_DIR})
# What `mc1 params` prints is its output: a standard output that cannot take
# it is a failure.
execute_process(COMMAND ${MC1} params OUTPUT_FILE /dev/full ERROR_VARIABLE err RESULT_VARIABLE rc)
if(NOT rc EQUAL 1 OR NOT err MATCHES "^mc1 params: standard output: No space left on device")
  message(SEND_ERROR "case params_stdout_full: exit ${rc}, ${err}")
endif()

# Every file option of every command in one check (cmdline::Files): a side
# file of the trace is an output too; an output given twice is refused (the
# first would be lost); sweep's --json, --out-dir and points, and --merge's
# reports, through links. Exit 2 before anything runs, nothing written.
expect(stats_is_trace_side 2 "--stats and --trace's side file name one file: ${WORK_DIR}/a\\.fst\\.kpc\\.txt"
       render ${tiny} --trace ${WORK_DIR}/a.fst --stats ${WORK_DIR}/a.fst.kpc.txt)
expect(gantt_is_trace_gtkw 2 "--gantt and --trace's side file name one file: ${WORK_DIR}/a\\.fst\\.gtkw"
       render ${tiny} --gantt ${WORK_DIR}/a.fst.gtkw --trace ${WORK_DIR}/a.fst)
# --profile is repeatable (p.md and p.json in one run: tests/workbench/repeated_outputs_test.sh), not on one file.
expect(profile_twice 2 "--profile and --profile name one file" render ${tiny} --profile ${WORK_DIR}/p.md --profile ${WORK_DIR}/p.md)
expect(stats_twice 2 "--stats is given 2 times" diag --nodes 2 --stats ${WORK_DIR}/s1.json --stats ${WORK_DIR}/s2.json)
expect(bench_json_is_params 2 "--json ${WORK_DIR}/w4.params would replace the timing table"
       bench --params ${WORK_DIR}/w4.params --json ${WORK_DIR}/w4.params)
foreach(f a.fst a.fst.kpc.txt a.fst.gtkw p.md p.json s1.json s2.json)
  if(EXISTS ${WORK_DIR}/${f})
    message(SEND_ERROR "an output of a refused command was written: ${f}")
  endif()
endforeach()
set(sweep sweep --scene ${WORK_DIR}/tiny.json --size 8x8 --nodes 2 --quiet)
expect(sweep_json_is_scene 2 "--json ${WORK_DIR}/tiny.json would replace the scene ${WORK_DIR}/tiny.json"
       ${sweep} --json ${WORK_DIR}/tiny.json)
file(REMOVE ${WORK_DIR}/tiny-link.json)
file(CREATE_LINK tiny.json ${WORK_DIR}/tiny-link.json SYMBOLIC)
expect(sweep_json_is_scene_link 2 "--json ${WORK_DIR}/tiny-link.json would replace the scene"
       ${sweep} --json ${WORK_DIR}/tiny-link.json)
file(READ ${WORK_DIR}/tiny.json scene_after)
if(NOT scene_after STREQUAL scene_before)
  message(SEND_ERROR "case sweep_json_is_scene: the scene was replaced")
endif()
file(MAKE_DIRECTORY ${WORK_DIR}/sw)
expect(sweep_json_is_point_png 2 "--json and --out-dir \\(--png frame\\) name one file: ${WORK_DIR}/sw/point-0000\\.png"
       ${sweep} --out-dir ${WORK_DIR}/sw --png --json ${WORK_DIR}/sw/point-0000.png)
expect(sweep_json_no_dir 2 "--json: ${WORK_DIR}/none/r.json: cannot open for writing"
       ${sweep} --out-dir ${WORK_DIR}/sw --json ${WORK_DIR}/none/r.json)
expect(sweep_out_dir_missing 2 "--out-dir \\(point statistics\\): ${WORK_DIR}/none/point-0000\\.json: cannot open for writing"
       ${sweep} --out-dir ${WORK_DIR}/none)
# A sweep that fails part way (the second scene is bad) leaves none of its files.
file(WRITE ${WORK_DIR}/bad.json "{\"camera\": ")
expect(sweep_fails 2 "bad\\.json" ${sweep} --scene ${WORK_DIR}/bad.json --out-dir ${WORK_DIR}/sw --png
       --json ${WORK_DIR}/sw/r.json)
file(GLOB written ${WORK_DIR}/sw/*)
if(written)
  message(SEND_ERROR "case sweep_fails: files of the failed sweep left: ${written}")
endif()
# --merge: the merged report on a shard's report, directly or through a link.
expect(sweep_one 0 "" ${sweep} --out-dir ${WORK_DIR}/sw --json ${WORK_DIR}/sw/r.json)
file(READ ${WORK_DIR}/sw/r.json report_before)
file(REMOVE ${WORK_DIR}/sw/r-link.json)
file(CREATE_LINK r.json ${WORK_DIR}/sw/r-link.json SYMBOLIC)
expect(merge_json_is_report 2 "--json ${WORK_DIR}/sw/r.json would replace the report ${WORK_DIR}/sw/r.json"
       sweep --merge ${WORK_DIR}/sw/r.json --json ${WORK_DIR}/sw/r.json)
expect(merge_json_is_report_link 2 "--json ${WORK_DIR}/sw/r-link.json would replace the report"
       sweep --merge ${WORK_DIR}/sw/r.json --json ${WORK_DIR}/sw/r-link.json)
file(READ ${WORK_DIR}/sw/r.json report_after)
if(NOT report_after STREQUAL report_before)
  message(SEND_ERROR "case merge_json_is_report: the shard's report was replaced")
endif()
file(REMOVE_RECURSE ${WORK_DIR}/sw)

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
