# A frame against the reference, as issue 14 asks: PSNR >= MIN_DB and no
# cluster of wrong pixels (8-connected, channel error > 32) over MAX_CLUSTER.
#   cmake -DMC1=<mc1> -DREF=<mc1-ref> -DPSNR=<mc1-psnr> -DSCENE=<scene.json> -DSIZE=WxH
#         -DOUT=<dir> [-DMIN_DB=45] [-DMAX_CLUSTER=4] [-DNODES=16] -P render_quality.cmake
if(NOT MIN_DB)
  set(MIN_DB 45)
endif()
if(NOT DEFINED MAX_CLUSTER)
  set(MAX_CLUSTER 4)
endif()
if(NOT NODES)
  set(NODES 16)
endif()
get_filename_component(name ${SCENE} NAME_WE)
file(MAKE_DIRECTORY ${OUT})
set(frame ${OUT}/${name}-${SIZE}.png)
set(ref ${OUT}/${name}-${SIZE}-ref.png)

function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  message(STATUS "${out}${err}")
  if(NOT rc EQUAL 0)
    list(GET ARGN 0 program)
    message(FATAL_ERROR "${program}: exit status ${rc}")
  endif()
endfunction()

run(${MC1} render ${SCENE} --size ${SIZE} --nodes ${NODES} --quiet --out ${frame})
run(${REF} ${SCENE} --size ${SIZE} --out ${ref})
run(${PSNR} ${frame} ${ref} --min ${MIN_DB} --max-cluster ${MAX_CLUSTER} --diff ${OUT}/${name}-${SIZE}-diff.png)
