# The renders whose profile guides the optimised build (cmake/ProfileGuided.cmake), run by the
# instrumented rtiow: the book's cover with each sampler (the independent one through
# bench-point, as benchmarks time it), a glass-and-metal scene, an adaptive render, and a big
# scene written to a file and rendered from it (without it the load of a big scene, code the
# training barely ran, was compiled with less inlining than a build without a profile).
# Small, so the training takes seconds. A failure leaves those paths without a profile (as with
# -DRTIOW_PGO=OFF) rather than failing the build.
#   cmake -DRTIOW=<instrumented rtiow> -DWORK_DIR=<dir> -P ProfileTraining.cmake
function(train)
  execute_process(COMMAND ${RTIOW} ${ARGN} RESULT_VARIABLE result OUTPUT_QUIET
                  ERROR_VARIABLE errors)
  if(NOT result EQUAL 0)
    message(WARNING "profile training: 'rtiow ${ARGN}' failed (${result}): ${errors}")
  endif()
endfunction()

set(small --width 160 --height 90 --quiet --checkpoint 0)
train(bench-point --scene cover --width 160 --height 90 --spp 64 --depth 50 --repeat 1
      --threads 2)
train(render --scene cover ${small} --spp 64 -o ${WORK_DIR}/train-sobol.png)
train(render --scene cover ${small} --spp 32 --sampler padded-sobol
      -o ${WORK_DIR}/train-padded.png)
train(render --scene materials ${small} --spp 64 -o ${WORK_DIR}/train-materials.png)
train(render --scene cover --width 80 --height 45 --image-error 0.05 --quiet --checkpoint 0
      -o ${WORK_DIR}/train-adaptive.png)
train(scene spheres:100000 -o ${WORK_DIR}/train-spheres.json)
train(render ${WORK_DIR}/train-spheres.json --width 8 --height 8 --spp 1 --quiet
      -o ${WORK_DIR}/train-spheres.png)
