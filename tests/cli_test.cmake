# CTest check: one program's command-line conventions (host/common/cmdline.hpp):
# --help and --version exit 0 on stdout; bad options, out-of-range numbers,
# missing files and directories exit 2 with a message naming the option or
# the file; a failed check or write exits 1.
#   cmake -DPROGRAM=name -DBIN=dir -DSRC=source-dir -DWORK_DIR=dir -DVERSION=x.y.z -P cli_test.cmake
file(MAKE_DIRECTORY ${WORK_DIR})
set(P ${BIN}/${PROGRAM})

# expect(CASE RC n [OUT regex] [ERR regex] [INPUT file] ARGS args...)
function(expect case)
  cmake_parse_arguments(E "" "RC;OUT;ERR;INPUT" "ARGS" ${ARGN})
  set(input "")
  if(DEFINED E_INPUT)
    set(input INPUT_FILE ${E_INPUT})
  endif()
  execute_process(COMMAND ${P} ${E_ARGS} ${input} WORKING_DIRECTORY ${WORK_DIR}
    OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE rc)
  set(ok TRUE)
  if(NOT rc STREQUAL E_RC)
    set(ok FALSE)
  endif()
  if(DEFINED E_OUT AND NOT out MATCHES "${E_OUT}")
    set(ok FALSE)
  endif()
  if(DEFINED E_ERR AND NOT err MATCHES "${E_ERR}")
    set(ok FALSE)
  endif()
  if(NOT ok)
    message(SEND_ERROR "${PROGRAM} ${case} (${E_ARGS}): exit ${rc}, wanted ${E_RC}\n"
                       "stdout: ${out}\nstderr: ${err}\nwanted stdout ~ '${E_OUT}', stderr ~ '${E_ERR}'")
  endif()
endfunction()

# expect_same(CASE FILE TEXT): FILE (in WORK_DIR) still holds TEXT.
function(expect_same case file text)
  file(READ ${WORK_DIR}/${file} now)
  if(NOT now STREQUAL text)
    message(SEND_ERROR "${PROGRAM} ${case}: ${file} was replaced: '${now}'")
  endif()
endfunction()

# expect_absent(CASE FILE...): none of FILE (in WORK_DIR) exists, and no
# staged temporary file is left in WORK_DIR.
function(expect_absent case)
  foreach(f ${ARGN})
    if(EXISTS ${WORK_DIR}/${f})
      message(SEND_ERROR "${PROGRAM} ${case}: ${f} was written")
    endif()
  endforeach()
  file(GLOB temps ${WORK_DIR}/.*.tmp.*)
  if(temps)
    message(SEND_ERROR "${PROGRAM} ${case}: temporary files left: ${temps}")
  endif()
endfunction()

# expect_stdout_full(CASE ARGS...): with standard output on /dev/full (read
# only: it is never a file argument), exit 1 and "PROGRAM: standard output:
# No space left on device" on stderr.
function(expect_stdout_full case)
  execute_process(COMMAND ${P} ${ARGN} WORKING_DIRECTORY ${WORK_DIR} OUTPUT_FILE /dev/full ERROR_VARIABLE err
    RESULT_VARIABLE rc)
  if(NOT rc EQUAL 1 OR NOT err MATCHES "${PROGRAM}: standard output: No space left on device")
    message(SEND_ERROR "${PROGRAM} ${case} (${ARGN}) > /dev/full: exit ${rc}, wanted 1; stderr: ${err}")
  endif()
endfunction()

# Every program: --help, --version, an unknown option.
string(REPLACE "." "\\." version_re "${VERSION}")
expect(help RC 0 OUT "Usage: ${PROGRAM}" ARGS --help)
expect(version RC 0 OUT "^${PROGRAM} \\(MC-1 virtual platform\\) ${version_re}\n$" ARGS --version)
expect(unknown_option RC 2 ERR "^${PROGRAM}: " ARGS --no-such-option)

set(docs ${SRC}/docs)
if(PROGRAM STREQUAL "fp24-run")
  file(WRITE ${WORK_DIR}/ok.vec "add 3f0000 3f0000\n")
  expect(ok RC 0 OUT "^400000 00\n$" INPUT ${WORK_DIR}/ok.vec ARGS --engine model)
  expect(stdin_directory RC 2 ERR "^fp24-run: standard input is a directory" INPUT ${docs} ARGS --engine model)
  expect(unknown_named RC 2 ERR "not expected: --bogus" INPUT ${WORK_DIR}/ok.vec ARGS --engine model --bogus)
  expect(no_engine RC 2 ERR "--engine is required" INPUT ${WORK_DIR}/ok.vec)
  expect(bad_engine RC 2 ERR "--engine: fpga not in" INPUT ${WORK_DIR}/ok.vec ARGS --engine fpga)
  # A waveform its writer cannot take is refused before the run; a good one
  # appears once the run is over, with no temporary file beside it.
  expect(trace_directory RC 2 ERR "--trace: ${docs}: cannot open for writing: is a directory" INPUT ${WORK_DIR}/ok.vec
         ARGS --engine rtl --trace ${docs})
  expect(trace_no_dir RC 2 ERR "--trace: none/t.fst: cannot open for writing: cannot create a temporary file beside it"
         INPUT ${WORK_DIR}/ok.vec ARGS --engine rtl --trace none/t.fst)
  expect(trace_ok RC 0 OUT "^400000 00\n$" INPUT ${WORK_DIR}/ok.vec ARGS --engine rtl --trace t.fst)
  file(GLOB temps ${WORK_DIR}/.t.fst.*)
  if(NOT EXISTS ${WORK_DIR}/t.fst OR temps)
    message(SEND_ERROR "fp24-run --trace t.fst: no t.fst, or temporary files left: ${temps}")
  endif()
  # No output replaces an input (cmdline::Files), standard input redirected
  # from a file included; a failed check leaves no waveform; what it prints
  # is its output.
  set(golden "add 3f0000 3f0000 400000 00\n")
  file(WRITE ${WORK_DIR}/g.golden "${golden}")
  expect(trace_is_golden RC 2 ERR "--trace g.golden would replace the golden file g.golden"
         ARGS --check g.golden --engine rtl --trace g.golden)
  expect_same(trace_is_golden g.golden "${golden}")
  file(REMOVE ${WORK_DIR}/g-link.golden)
  file(CREATE_LINK g.golden ${WORK_DIR}/g-link.golden SYMBOLIC)
  expect(trace_is_golden_link RC 2 ERR "--trace g-link.golden would replace the golden file g.golden"
         ARGS --check g.golden --engine rtl --trace g-link.golden)
  expect_same(trace_is_golden_link g.golden "${golden}")
  expect(trace_is_stdin RC 2 ERR "--trace g.golden would replace standard input" INPUT ${WORK_DIR}/g.golden
         ARGS --check - --engine rtl --trace g.golden)
  expect_same(trace_is_stdin g.golden "${golden}")
  file(WRITE ${WORK_DIR}/v.vec "add 3f0000 3f0000\n")
  expect(trace_is_vectors RC 2 ERR "--trace v.vec would replace standard input" INPUT ${WORK_DIR}/v.vec
         ARGS --engine rtl --trace v.vec)
  expect_same(trace_is_vectors v.vec "add 3f0000 3f0000\n")
  file(WRITE ${WORK_DIR}/wrong.golden "add 3f0000 3f0000 400001 00\n")
  expect(check_fails_no_trace RC 1 OUT "1 mismatch: FAIL" ARGS --check wrong.golden --engine rtl --trace w.fst)
  expect_absent(check_fails_no_trace w.fst)
  expect(check_passes_trace RC 0 OUT "0 mismatches: PASS" ARGS --check g.golden --engine rtl --trace p.fst)
  if(NOT EXISTS ${WORK_DIR}/p.fst)
    message(SEND_ERROR "fp24-run --check g.golden --trace p.fst: no p.fst")
  endif()
  expect_stdout_full(stdout_full_check --check g.golden --engine model)
  execute_process(COMMAND ${P} --engine model INPUT_FILE ${WORK_DIR}/ok.vec OUTPUT_FILE /dev/full
    ERROR_VARIABLE err RESULT_VARIABLE rc)
  if(NOT rc EQUAL 1 OR NOT err MATCHES "^fp24-run: standard output: No space left on device")
    message(SEND_ERROR "fp24-run --engine model > /dev/full: exit ${rc}, stderr '${err}'")
  endif()
elseif(PROGRAM STREQUAL "fp24-regress")
  set(quick --ops neg --no-rtl --no-oracle --random 0)
  expect(threads_zero RC 2 ERR "--threads: '0' is out of range \\[1, 1024\\]" ARGS ${quick} --threads 0)
  expect(show_too_big RC 2 ERR "--show: '99999999999' is out of range" ARGS ${quick} --show 99999999999)
  expect(seed_too_big RC 2 ERR "--seed: '99999999999999999999' is out of range"
         ARGS ${quick} --seed 99999999999999999999)
  expect(random_negative RC 2 ERR "--random: '-1' is not a number" ARGS ${quick} --random -1)
  expect(unknown_op RC 2 ERR "--ops: unknown op 'fma'" ARGS --ops fma)
  expect(report_dir RC 2 ERR "/no/such/dir/r.txt: cannot open for writing" ARGS ${quick} --text /no/such/dir/r.txt)
elseif(PROGRAM STREQUAL "fp24-conv")
  expect(converts RC 0 OUT "^1.5: 3f8000 flags 00" ARGS 1.5)
  expect(no_value RC 2 ERR "VALUE is required" ARGS --flags)
  expect(not_number RC 2 ERR "^fp24-conv: VALUE 'x': not a decimal number" ARGS x)
  expect(hex_too_wide RC 2 ERR "VALUE: '0x1000000' is out of range" ARGS 0x1000000)
  expect(bad_flags RC 2 ERR "VALUE 'XX': not flags" ARGS --flags XX)
  # -inf and -nan are values, not options, wherever they stand.
  expect(negative_inf RC 0 OUT "^1.5: 3f8000[^\n]*\n-inf: ff0000 flags 00 \\(-\\), reads back -inf\n$" ARGS 1.5 -inf)
  # What it prints is its output: a standard output that cannot take it is a failure.
  execute_process(COMMAND ${P} 1.5 OUTPUT_FILE /dev/full ERROR_VARIABLE err RESULT_VARIABLE rc)
  if(NOT rc EQUAL 1 OR NOT err MATCHES "^fp24-conv: standard output: No space left on device")
    message(SEND_ERROR "fp24-conv 1.5 > /dev/full: exit ${rc}, ${err}")
  endif()
elseif(PROGRAM STREQUAL "fp24-bench")
  expect(seconds_nan RC 2 ERR "--seconds: 'nan' is out of range" ARGS --seconds nan)
  expect(seconds_text RC 2 ERR "--seconds: '1s' is not a number" ARGS --seconds 1s)
  expect_stdout_full(stdout_full --seconds 0.001 --no-rtl)
elseif(PROGRAM STREQUAL "apuasm")
  file(WRITE ${WORK_DIR}/halt.apu "  halt\n")
  expect(assembles RC 0 ARGS halt.apu -o halt.bin)
  expect(missing RC 2 ERR "none.apu: error: cannot read file" ARGS none.apu -o none.bin)
  expect(nothing RC 2 ERR "^apuasm: " ARGS)
  expect(image_is_source RC 2 ERR "-o halt.apu would replace the source halt.apu" ARGS halt.apu -o halt.apu)
  expect_same(image_is_source halt.apu "  halt\n")
  expect(listing_is_image RC 2 ERR "-o and -l name one file: ./h.bin" ARGS halt.apu -o h.bin -l ./h.bin)
  file(WRITE ${WORK_DIR}/inc.apu "  .include \"halt.apu\"\n")
  expect(hex_is_include RC 2 ERR "-x halt.apu would replace the include file" ARGS inc.apu -x halt.apu)
  expect_same(hex_is_include halt.apu "  halt\n")
elseif(PROGRAM STREQUAL "apu-run")
  file(WRITE ${WORK_DIR}/halt.apu "  halt\n")
  file(WRITE ${WORK_DIR}/loop.apu "loop: jmp loop\n")
  expect(halts RC 0 OUT "halt.apu on iss: halted after" ARGS halt.apu)
  expect(start_hex RC 0 OUT "halted after" ARGS halt.apu --start 0x0 --max-cycles 1000)
  expect(cycle_limit RC 1 OUT "cycle limit" ARGS loop.apu --max-cycles 100)
  expect(max_cycles_too_big RC 2 ERR "--max-cycles: '99999999999999999999' is out of range"
         ARGS halt.apu --max-cycles 99999999999999999999)
  expect(max_cycles_zero RC 2 ERR "--max-cycles: '0' is out of range" ARGS halt.apu --max-cycles 0)
  expect(start_too_big RC 2 ERR "--start: '5000' is out of range \\[0, 1023\\]" ARGS halt.apu --start 5000)
  expect(start_octal RC 2 ERR "--start: '010': a leading 0" ARGS halt.apu --start 010)
  expect(top_negative RC 2 ERR "--top: '-1' is not a number" ARGS halt.apu --profile --top -1)
  expect(read_past_end RC 2 ERR "--read 4090:10 goes past word 4095" ARGS halt.apu --read 4090:10)
  expect(read_not_pair RC 2 ERR "--read wants ADDR:COUNT" ARGS halt.apu --read 12)
  expect(program_missing RC 2 ERR "PROGRAM: nothing.apu: No such file" ARGS nothing.apu)
  expect(program_directory RC 2 ERR "PROGRAM: ${docs}: is a directory" ARGS ${docs})
  expect(data_directory RC 2 ERR "--data: ${docs}: is a directory" ARGS halt.apu --data ${docs})
  expect(unknown_named RC 2 ERR "not expected: --bogus" ARGS halt.apu --bogus)
  expect(two_programs RC 2 ERR "apu-run: " ARGS halt.apu loop.apu)
  expect(bad_engine RC 2 ERR "--engine: fpga not in" ARGS halt.apu --engine fpga)
  expect(trace_switches_to_rtl RC 0 OUT "halt.apu on rtl: halted" ERR "--trace: running on the RTL core"
         ARGS halt.apu --trace t.fst)
  expect(trace_directory RC 2 ERR "--trace: ${docs}: cannot open for writing: is a directory" ARGS halt.apu --engine rtl --trace ${docs})
  expect(trace_device RC 2 ERR "--trace: /dev/null: is not a regular file"
         ARGS halt.apu --engine rtl --trace /dev/null)
  # A waveform cut short (the file size limit stands in for a full disk: the
  # FST writer's writes fail past 100 KB): exit 1, and neither the FST nor
  # any of its side files goes in place (the side files are committed after it).
  file(WRITE ${WORK_DIR}/long.apu "  li a1, 3000\nouter:\n  li a2, 100\ninner:\n  add f1, f1, f2 | dbnz a2, inner\n  dbnz a1, outer\n  halt\n")
  # The work directory outlives a run: what an earlier run left must not
  # pass for this one's.
  file(GLOB stale_cut_files ${WORK_DIR}/cut.fst*)
  if(stale_cut_files)
    file(REMOVE ${stale_cut_files})
  endif()
  execute_process(COMMAND sh -c "trap '' XFSZ; ulimit -f 200; exec \"$0\" long.apu --engine rtl --trace cut.fst" ${P}
                  WORKING_DIRECTORY ${WORK_DIR} OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE rc)
  if(NOT rc EQUAL 1 OR NOT err MATCHES "cut.fst: the waveform was not written whole")
    message(SEND_ERROR "apu-run --trace past the file size limit: exit ${rc}, wanted 1; stderr: ${err}")
  endif()
  file(GLOB cut_files ${WORK_DIR}/cut.fst*)
  if(cut_files)
    message(SEND_ERROR "apu-run --trace cut short left: ${cut_files}")
  endif()
  expect_absent(trace_cut_short cut.fst)
  # The stall profile as JSON (apu-profile/2): a RAW stall at pc 3 each of 20
  # rounds, one cycle each; the start's fetch and decode and the loop exit's
  # branch miss are `fetch` stalls (docs/apu-isa.md "Timing").
  file(WRITE ${WORK_DIR}/stall.apu "  li a1, 20\nloop:\n  lif f1, 1.5\n  mul f2, f1, f1\n  add f3, f2, f1\n  dbnz a1, loop\n  halt\n")
  foreach(engine iss rtl)
    file(REMOVE ${WORK_DIR}/p.json)
    expect(profile_json_${engine} RC 0 ARGS stall.apu --engine ${engine} --profile-json p.json)
    file(READ ${WORK_DIR}/p.json pj)
    if(NOT pj MATCHES "^{\"schema\": \"apu-profile/2\", \"source\": \"apu-run\", \"program\": \"stall.apu\","
       OR NOT pj MATCHES "\"totals\": {\"cycles\": 105, \"issued\": 82, \"faulted\": 0, \"stalled\": 23, \"stalls\": {\"bank\": 0, \"raw\": 20, \"waw\": 0, \"cc\": 0, \"drain\": 0, \"fetch\": 3}}"
       OR NOT pj MATCHES "{\"pc\": 3, \"word\": \"add f3, f2, f1\", \"cycles\": 40, \"issued\": 20, \"faulted\": 0, \"stalled\": 20, [^\n]*\"raw\": 20[^\n]*\"worst\": {\"time_ps\": [0-9]+, \"nc\": 1, \"cycles\": 1}")
      message(SEND_ERROR "apu-run --profile-json on ${engine}: ${pj}")
    endif()
  endforeach()
  expect(profile_json_full RC 1 ERR "--profile-json: /dev/full" ARGS stall.apu --profile-json /dev/full)
  # A trace comes with its (kernel, pc)-to-disassembly filter and save file
  # (the signals themselves: tb/apu/apu_run_trace.cmake).
  expect(trace_pc RC 0 ARGS stall.apu --engine rtl --trace s.fst)
  file(READ ${WORK_DIR}/s.fst.kpc.txt pcs)
  if(NOT pcs MATCHES "\n0001003 add f3, f2, f1\n0001004 dbnz a1, ")
    message(SEND_ERROR "apu-run --trace: s.fst.kpc.txt: ${pcs}")
  endif()
  if(NOT EXISTS ${WORK_DIR}/s.fst.gtkw)
    message(SEND_ERROR "apu-run --trace s.fst wrote no s.fst.gtkw")
  endif()
  file(READ ${WORK_DIR}/s.fst.kernel.txt kernel_ids)
  if(NOT kernel_ids MATCHES "\n0000 -\n0001 stall.apu\n$")
    message(SEND_ERROR "apu-run --trace: s.fst.kernel.txt: ${kernel_ids}")
  endif()
  # No output replaces an input or another output, side files of the trace
  # included, through symbolic and hard links (cmdline::Files); refused
  # before the run.
  file(WRITE ${WORK_DIR}/src.apu "  halt\n")
  file(REMOVE ${WORK_DIR}/src-sym.apu ${WORK_DIR}/src-hard.apu)
  file(CREATE_LINK src.apu ${WORK_DIR}/src-sym.apu SYMBOLIC)
  file(CREATE_LINK ${WORK_DIR}/src.apu ${WORK_DIR}/src-hard.apu)
  expect(trace_is_program RC 2 ERR "--trace src.apu would replace the program src.apu"
         ARGS src.apu --engine rtl --trace src.apu)
  expect(profile_json_is_program RC 2 ERR "--profile-json src-sym.apu would replace the program src.apu"
         ARGS src.apu --profile-json src-sym.apu)
  expect(profile_json_is_hard_link RC 2 ERR "--profile-json src-hard.apu would replace the program src.apu"
         ARGS src.apu --profile-json src-hard.apu)
  expect_same(outputs_on_program src.apu "  halt\n")
  file(WRITE ${WORK_DIR}/d.hex "@0 3f0000\n")
  expect(profile_json_is_data RC 2 ERR "--profile-json d.hex would replace the data file d.hex"
         ARGS src.apu --data d.hex --profile-json d.hex)
  expect_same(profile_json_is_data d.hex "@0 3f0000\n")
  file(WRITE ${WORK_DIR}/inc.inc "  nop\n")
  file(WRITE ${WORK_DIR}/main.apu "  .include \"inc.inc\"\n  halt\n")
  expect(profile_json_is_include RC 2 ERR "--profile-json inc.inc would replace the include file"
         ARGS main.apu --profile-json inc.inc)
  expect_same(profile_json_is_include inc.inc "  nop\n")
  foreach(side .gtkw .kpc.txt .kernel.txt)
    expect(profile_json_is_trace${side} RC 2 ERR "--trace's side file and --profile-json name one file: x.fst${side}"
           ARGS src.apu --engine rtl --trace x.fst --profile-json x.fst${side})
  endforeach()
  expect(profile_json_twice RC 2 ERR "--profile-json" ARGS src.apu --profile-json a.json --profile-json b.json)
  expect(profile_json_no_dir RC 2 ERR "--profile-json: none/p.json: cannot open for writing" ARGS src.apu --profile-json none/p.json)
  # A failed run (cycle limit, fault) leaves no waveform, side file or profile.
  expect(failed_run_no_outputs RC 1 OUT "cycle limit"
         ARGS loop.apu --engine rtl --max-cycles 100 --trace f.fst --profile-json f.json)
  expect_absent(failed_run_no_outputs f.fst f.fst.gtkw f.fst.kpc.txt f.fst.kernel.txt f.json)
  file(WRITE ${WORK_DIR}/fault.apu "  li a1, 4095\n  ld f1, [a1+1]\n  halt\n")
  expect(fault_no_outputs RC 1 ARGS fault.apu --engine rtl --trace g.fst --profile-json g.json)
  expect_absent(fault_no_outputs g.fst g.fst.gtkw g.fst.kpc.txt g.fst.kernel.txt g.json)
  expect_stdout_full(stdout_full halt.apu)
elseif(PROGRAM STREQUAL "apu-cosim")
  file(WRITE ${WORK_DIR}/halt.apu "  halt\n")
  expect(random_ok RC 0 OUT "3 random programs \\(seed 4\\), iss and iss agree"
         ARGS --random 3 --seed 4 --engines iss,iss)
  expect(program_ok RC 0 OUT "iss and iss agree" ARGS halt.apu --engines iss,iss)
  expect(random_zero RC 2 ERR "--random: '0' is out of range" ARGS --random 0)
  expect(seed_alone RC 2 ERR "--seed requires --random" ARGS halt.apu --seed 3)
  expect(both RC 2 ERR "excludes" ARGS halt.apu --random 3)
  expect(neither RC 2 ERR "no program and no --random" ARGS --engines iss,iss)
  expect(one_engine RC 2 ERR "--engines: wants A,B" ARGS --random 1 --engines iss)
  expect(max_cycles_too_big RC 2 ERR "--max-cycles: '18446744073709551616' is out of range"
         ARGS --random 1 --max-cycles 18446744073709551616)
  expect(program_directory RC 2 ERR "PROGRAM: ${docs}: is a directory" ARGS ${docs})
  expect(first_past_end RC 2 ERR "--first 18446744073709551615 with --random 2: the case indices pass 2\\^64 - 1"
         ARGS --random 2 --first 18446744073709551615 --engines iss,iss)
  expect(trace_no_rtl RC 2 ERR "--trace needs the rtl engine in --engines" ARGS halt.apu --engines iss,iss --trace t.fst)
  expect(trace_no_dir RC 2 ERR "--trace: none/t.fst: cannot open for writing: cannot create a temporary file beside it"
         ARGS halt.apu --trace none/t.fst)
  expect(trace_rtl_rtl RC 0 OUT "rtl and rtl agree" ARGS halt.apu --engines rtl,rtl --trace t.fst)
  file(GLOB temps ${WORK_DIR}/.t.fst.*)
  if(NOT EXISTS ${WORK_DIR}/t.fst OR temps)
    message(SEND_ERROR "apu-cosim --trace t.fst: no t.fst, or temporary files left: ${temps}")
  endif()
  expect(trace_is_program RC 2 ERR "--trace halt.apu would replace the program halt.apu" ARGS halt.apu --trace halt.apu)
  expect_same(trace_is_program halt.apu "  halt\n")
  file(WRITE ${WORK_DIR}/d.hex "@0 3f0000\n")
  expect(trace_is_data RC 2 ERR "--trace ./d.hex would replace the data file d.hex" ARGS halt.apu --data d.hex --trace ./d.hex)
  expect_same(trace_is_data d.hex "@0 3f0000\n")
  file(WRITE ${WORK_DIR}/inc.inc "  nop\n")
  file(WRITE ${WORK_DIR}/main.apu "  .include \"inc.inc\"\n  halt\n")
  expect(trace_is_include RC 2 ERR "--trace inc.inc would replace the include file" ARGS main.apu --trace inc.inc)
  expect_same(trace_is_include inc.inc "  nop\n")
  expect_stdout_full(stdout_full halt.apu --engines iss,iss)
  expect_stdout_full(stdout_full_random --random 2 --engines iss,iss)
elseif(PROGRAM STREQUAL "apu-bench")
  expect(bad_engine RC 2 ERR "--engines: fpga not in" ARGS --engines iss,fpga)
  expect(cycles_too_big RC 2 ERR "--iss-cycles: '99999999999999999999' is out of range"
         ARGS --iss-cycles 99999999999999999999)
  expect(kernel_directory RC 2 ERR "--kernel: ${docs}: is a directory" ARGS --kernel ${docs})
  # A kernel that assembles but faults is a failed run, not bad input.
  file(WRITE ${WORK_DIR}/fault.apu "  li a1, 4095\n  ld f1, [a1+1]\n  halt\n")
  expect(kernel_faults RC 1 ERR "^apu-bench: APU fault data-address" ARGS --kernel fault.apu --engines iss --iss-cycles 1000)
  expect(kernel_not_image RC 2 ERR "^apu-bench: .*README.md: not an APU image" ARGS --kernel ${SRC}/README.md --engines iss)
  expect_stdout_full(stdout_full --engines iss --iss-cycles 1000)
  # The ISS's row comes with the arithmetic alone, checked like an engine.
  expect(arithmetic_alone RC 0 OUT "\narithmetic alone \\(no engine[^\n]*: ok, 1000 vertices, [^\n]*the ISS [0-9.]+ of it\n"
         ARGS --engines iss --iss-cycles 16000)
elseif(PROGRAM STREQUAL "mc1-ref")
  expect(missing_scene RC 2 ERR "SCENE: none.json: No such file" ARGS none.json --out r.png)
  expect(scene_directory RC 2 ERR "SCENE: ${docs}: is a directory" ARGS ${docs} --out r.png)
  expect(no_out RC 2 ERR "--out is required" ARGS ${SRC}/scenes/tiny.json)
  expect(size_too_big RC 2 ERR "--size 10x99999: '99999' is out of range \\[1, 8192\\]"
         ARGS ${SRC}/scenes/tiny.json --size 10x99999 --out r.png)
  expect(size_not_pair RC 2 ERR "--size: expected WxH" ARGS ${SRC}/scenes/tiny.json --size 10 --out r.png)
  expect(write_failed RC 1 ERR "/dev/full: cannot write: No space left on device"
         ARGS ${SRC}/scenes/tiny.json --size 8x8 --out /dev/full)
  expect(renders RC 0 ERR "8x8, 3 primitives" ARGS ${SRC}/scenes/tiny.json --size 8x8 --out tiny8.png)
  file(COPY ${SRC}/scenes/tiny.json DESTINATION ${WORK_DIR})
  file(READ ${WORK_DIR}/tiny.json scene_before)
  expect(out_is_scene RC 2 ERR "--out ./tiny.json would replace the scene tiny.json" ARGS tiny.json --out ./tiny.json)
  file(READ ${WORK_DIR}/tiny.json scene_after)
  if(NOT scene_after STREQUAL scene_before)
    message(SEND_ERROR "mc1-ref --out tiny.json replaced the scene")
  endif()
  file(REMOVE ${WORK_DIR}/tiny-hard.json)
  file(CREATE_LINK ${WORK_DIR}/tiny.json ${WORK_DIR}/tiny-hard.json)
  expect(out_is_scene_hard_link RC 2 ERR "--out tiny-hard.json would replace the scene tiny.json"
         ARGS tiny.json --out tiny-hard.json)
  expect_same(out_is_scene_hard_link tiny.json "${scene_before}")
  # An --out that cannot be written is found before the render, not after it.
  expect(out_no_dir RC 2 ERR "--out: none/r.png: cannot open for writing" ARGS tiny.json --out none/r.png)
elseif(PROGRAM STREQUAL "mc1-psnr")
  # Two PNGs made by mc1-ref (the tests run it first: FIXTURES).
  file(WRITE ${WORK_DIR}/bad.png "not a PNG\n")
  expect(same RC 0 OUT "^PSNR inf dB.*clusters 0 \\(error > 32: 0 pixels\\)" ARGS tiny8.png tiny8.png --min 40 --max-cluster 0)
  expect(threshold_too_big RC 2 ERR "--threshold: '255' is out of range \\[0, 254\\]"
         ARGS tiny8.png tiny8.png --threshold 255)
  expect(one_file RC 2 ERR "FILES" ARGS tiny8.png)
  expect(missing RC 2 ERR "FILES: none.png: No such file" ARGS tiny8.png none.png)
  expect(directory RC 2 ERR "FILES: ${docs}: is a directory" ARGS tiny8.png ${docs})
  expect(not_png RC 2 ERR "^mc1-psnr: bad.png: Not a PNG file" ARGS tiny8.png bad.png)
  expect(scale_too_big RC 2 ERR "--scale: '99999999999' is out of range \\[1, 255\\]"
         ARGS tiny8.png tiny8.png --scale 99999999999)
  expect(min_nan RC 2 ERR "--min: 'nan' is out of range" ARGS tiny8.png tiny8.png --min nan)
  expect(diff_failed RC 1 ERR "/dev/full: cannot write" ARGS tiny8.png tiny8.png --diff /dev/full)
  file(SHA256 ${WORK_DIR}/tiny8.png png_before)
  expect(diff_is_input RC 2 ERR "--diff tiny8.png would replace the image tiny8.png" ARGS tiny8.png tiny8.png --diff tiny8.png)
  file(SHA256 ${WORK_DIR}/tiny8.png png_after)
  if(NOT png_after STREQUAL png_before)
    message(SEND_ERROR "mc1-psnr --diff tiny8.png replaced the input")
  endif()
  file(REMOVE ${WORK_DIR}/tiny8-sym.png)
  file(CREATE_LINK tiny8.png ${WORK_DIR}/tiny8-sym.png SYMBOLIC)
  expect(diff_is_input_link RC 2 ERR "--diff tiny8-sym.png would replace the image tiny8.png"
         ARGS tiny8.png tiny8.png --diff tiny8-sym.png)
  file(SHA256 ${WORK_DIR}/tiny8.png png_after)
  if(NOT png_after STREQUAL png_before)
    message(SEND_ERROR "mc1-psnr --diff tiny8-sym.png replaced the input")
  endif()
  expect(diff_no_dir RC 2 ERR "--diff: none/d.png: cannot open for writing" ARGS tiny8.png tiny8.png --diff none/d.png)
  expect_stdout_full(stdout_full tiny8.png tiny8.png)
else()
  message(FATAL_ERROR "cli_test.cmake: no cases for ${PROGRAM}")
endif()
