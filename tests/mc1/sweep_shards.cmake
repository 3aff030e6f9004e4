# mc1 sweep --shard / --merge without SLURM (docs/platform.md "Sweeps on a
# SLURM cluster"): a 16-point grid (tiny.json at 32x32, 2 orbit frames x 1, 4
# NCs x lpt, static x blocks 8, 16x8) run whole and as 3 shards through the
# SLURM task files themselves (tools/slurm/mc1-sweep-shard.sbatch with
# SLURM_ARRAY_TASK_ID set, then mc1-sweep-merge.sbatch): the merged report
# equals the whole run's but for host times and "shard", every point's
# statistics equal the whole run's, every frame is equal across its points;
# a missing or repeated shard is a usage error.
#   cmake -DMC1=<mc1> -DSRC=<source dir> -DWORK_DIR=<dir> -P sweep_shards.cmake
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR}/whole)
set(grid --scene ${SRC}/scenes/tiny.json --size 32x32 --orbit 2 --nodes 1,4 --schedules lpt,static --blocks 8,16x8)

function(must rc_want)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL rc_want)
    message(FATAL_ERROR "${ARGN}: exit ${rc}, wanted ${rc_want}\n${out}\n${err}")
  endif()
  set(last_err "${err}" PARENT_SCOPE)
endfunction()

# Without its host figures (and the merged report's "shard").
function(sim_lines in out)
  file(STRINGS ${in} lines)
  list(FILTER lines EXCLUDE REGEX "\"host\"|\"shard\"|wall_seconds|\"threads\"")
  list(TRANSFORM lines REPLACE ", \"host_seconds\": [0-9.e+-]+" "")
  string(REPLACE ";" "\n" lines "${lines}")
  file(WRITE ${out} "${lines}\n")
endfunction()

must(0 ${MC1} sweep ${grid} --threads 2 --quiet --out-dir ${WORK_DIR}/whole --json ${WORK_DIR}/whole/report.json)
must(0 ${MC1} sweep --merge ${WORK_DIR}/whole/report.json --json ${WORK_DIR}/whole/merged.json --quiet)

foreach(k 1 2 3)
  must(0 ${CMAKE_COMMAND} -E env SLURM_ARRAY_TASK_ID=${k} SLURM_CPUS_PER_TASK=2
       sh ${SRC}/tools/slurm/mc1-sweep-shard.sbatch ${WORK_DIR}/sharded ${MC1} 3 0 ${grid})
endforeach()
must(0 sh ${SRC}/tools/slurm/mc1-sweep-merge.sbatch ${WORK_DIR}/sharded ${MC1} 3)

sim_lines(${WORK_DIR}/whole/merged.json ${WORK_DIR}/whole.sim)
sim_lines(${WORK_DIR}/sharded/merged.json ${WORK_DIR}/sharded.sim)
execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${WORK_DIR}/whole.sim ${WORK_DIR}/sharded.sim RESULT_VARIABLE d)
if(NOT d EQUAL 0)
  message(FATAL_ERROR "the merge of 3 shards differs from the whole run (${WORK_DIR}/whole.sim, sharded.sim)")
endif()
file(READ ${WORK_DIR}/sharded/merged.json merged)
string(JSON shard GET "${merged}" shard)
string(JSON points LENGTH "${merged}" points)
string(JSON frames LENGTH "${merged}" frames)
string(JSON equal0 GET "${merged}" frames 0 equal)
string(JSON passed GET "${merged}" passed)
if(NOT shard STREQUAL "all/3" OR NOT points EQUAL 16 OR NOT frames EQUAL 2 OR NOT equal0 OR NOT passed)
  message(FATAL_ERROR "merged: shard ${shard}, ${points} points, ${frames} frames, equal ${equal0}, passed ${passed}")
endif()
foreach(i RANGE 15)
  string(JSON stats GET "${merged}" points ${i} stats)
  sim_lines(${WORK_DIR}/whole/${stats} ${WORK_DIR}/a.sim)
  sim_lines(${WORK_DIR}/sharded/points/${stats} ${WORK_DIR}/b.sim)
  execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${WORK_DIR}/a.sim ${WORK_DIR}/b.sim RESULT_VARIABLE d)
  if(NOT d EQUAL 0)
    message(FATAL_ERROR "${stats}: the shard's statistics differ from the whole run's")
  endif()
endforeach()

must(2 ${MC1} sweep --merge ${WORK_DIR}/sharded/shard-1.json ${WORK_DIR}/sharded/shard-3.json)
if(NOT last_err MATCHES "shard 2/3 missing")
  message(FATAL_ERROR "a missing shard: ${last_err}")
endif()
must(2 ${MC1} sweep --merge ${WORK_DIR}/sharded/shard-1.json ${WORK_DIR}/sharded/shard-1.json
     ${WORK_DIR}/sharded/shard-2.json)
if(NOT last_err MATCHES "shard 1 given twice")
  message(FATAL_ERROR "a repeated shard: ${last_err}")
endif()
must(2 ${MC1} sweep --merge ${WORK_DIR}/sharded/merged.json)
if(NOT last_err MATCHES "is not K/N")
  message(FATAL_ERROR "a merged report as a shard: ${last_err}")
endif()
# A shard whose points say what no run can: refused naming the file and line.
file(READ ${WORK_DIR}/sharded/shard-1.json shard1)
string(REGEX REPLACE "\"nodes\": [0-9]+" "\"nodes\": -3" bad "${shard1}")
file(WRITE ${WORK_DIR}/sharded/bad-1.json "${bad}")
must(2 ${MC1} sweep --merge ${WORK_DIR}/sharded/bad-1.json ${WORK_DIR}/sharded/shard-2.json
     ${WORK_DIR}/sharded/shard-3.json)
if(NOT last_err MATCHES "bad-1.json:[0-9]+: \"nodes\" is -3, not a count")
  message(FATAL_ERROR "a negative NC count: ${last_err}")
endif()
# A point marked incomplete in a shard that says it passed: the merge fails
# (exit 1, "passed": false), as the point says, not as the shard says.
string(REGEX REPLACE "(\"index\": 1,[^\n]*\"complete\": )true" "\\1false" bad "${shard1}")
file(WRITE ${WORK_DIR}/sharded/incomplete-1.json "${bad}")
must(1 ${MC1} sweep --merge ${WORK_DIR}/sharded/incomplete-1.json ${WORK_DIR}/sharded/shard-2.json
     ${WORK_DIR}/sharded/shard-3.json --json ${WORK_DIR}/sharded/incomplete-merged.json --quiet)
file(READ ${WORK_DIR}/sharded/incomplete-merged.json merged)
string(JSON passed GET "${merged}" passed)
if(passed)
  message(FATAL_ERROR "an incomplete point merged to passed")
endif()
# A point that is not the grid's point of its index (its NC count, its
# scene): refused naming the file and line.
string(REGEX REPLACE "(\"index\": 1,[^\n]*\"nodes\": )1," "\\14," bad "${shard1}")
file(WRITE ${WORK_DIR}/sharded/offgrid-1.json "${bad}")
must(2 ${MC1} sweep --merge ${WORK_DIR}/sharded/offgrid-1.json ${WORK_DIR}/sharded/shard-2.json
     ${WORK_DIR}/sharded/shard-3.json)
if(NOT last_err MATCHES "offgrid-1.json:[0-9]+: point 1 \\(.*tiny.json, 4 NCs, frame 0\\) is not the grid's point 1")
  message(FATAL_ERROR "a point off the grid: ${last_err}")
endif()
string(REPLACE "scenes/tiny.json\", \"frame\": 0, \"orbit_deg\": 0, \"nodes\": 1, \"schedule\": \"lpt\", \"block\": \"16x8\""
       "scenes/room.json\", \"frame\": 0, \"orbit_deg\": 0, \"nodes\": 1, \"schedule\": \"lpt\", \"block\": \"16x8\"" bad "${shard1}")
file(WRITE ${WORK_DIR}/sharded/offgrid-1.json "${bad}")
must(2 ${MC1} sweep --merge ${WORK_DIR}/sharded/offgrid-1.json ${WORK_DIR}/sharded/shard-2.json
     ${WORK_DIR}/sharded/shard-3.json)
if(NOT last_err MATCHES "is not the grid's point 1")
  message(FATAL_ERROR "a point of another scene: ${last_err}")
endif()
message(STATUS "16 points whole and in 3 shards: the same report and statistics")
