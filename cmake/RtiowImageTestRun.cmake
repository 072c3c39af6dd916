# One image test of rtiow_add_image_test (cmake/RtiowImageTest.cmake), run by CTest as
#   cmake -DSETTINGS=<name>.cmake -P RtiowImageTestRun.cmake
# SETTINGS sets TEST_NAME, RTIOW, reference, render_args, work_dir, SPP, SEEDS, REFERENCE_SPP,
# DIFF_ARGS and EXPECT_FAILURE.
include(${SETTINGS})

function(run_rtiow what)
  execute_process(COMMAND ${RTIOW} ${ARGN} RESULT_VARIABLE code OUTPUT_VARIABLE out
                  ERROR_VARIABLE err)
  if(NOT code EQUAL 0)
    string(REPLACE ";" " " command "${ARGN}")
    message(FATAL_ERROR "${what} failed (exit ${code}): rtiow ${command}\n${out}${err}")
  endif()
endfunction()

if("$ENV{RTIOW_UPDATE_REFERENCES}" AND EXPECT_FAILURE)
  message(STATUS "updating references: a test that must fail has none of its own")
  return()
elseif("$ENV{RTIOW_UPDATE_REFERENCES}")
  get_filename_component(directory ${reference} DIRECTORY)
  file(MAKE_DIRECTORY ${directory})
  # No checkpoint: a reference is kept in a source tree, and a finished render's checkpoint
  # (kept for refining it with --resume) would land beside it.
  run_rtiow("rendering the reference" render -q ${render_args} --spp ${REFERENCE_SPP} --seed 0
            --stats-channels --checkpoint 0 -o ${reference})
  message(STATUS "wrote the reference ${reference} (${REFERENCE_SPP} spp, seed 0)")
  return()
endif()
if(NOT EXISTS ${reference})
  message(FATAL_ERROR "the reference ${reference} does not exist; make it with\n"
                      "  RTIOW_UPDATE_REFERENCES=1 ctest -R '^${TEST_NAME}$'")
endif()

file(REMOVE_RECURSE ${work_dir})
file(MAKE_DIRECTORY ${work_dir})
set(renders "")
foreach(seed RANGE 1 ${SEEDS})
  set(image ${work_dir}/seed-${seed}.exr)
  run_rtiow("rendering seed ${seed}" render -q ${render_args} --spp ${SPP} --seed ${seed}
            -o ${image})
  list(APPEND renders ${image})
endforeach()

execute_process(
  COMMAND ${RTIOW} diff ${reference} ${renders} --mode seeds --out-diff ${work_dir}/diff.png
          --out-z ${work_dir}/z.png ${DIFF_ARGS}
  RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}${err}")
# rtiow diff exits as idiff does: 0 pass, 1 warning, 2 failure; 3 and 4 when it could not
# compare (images of other sizes; a file or option it cannot use).
if(code EQUAL 2)
  if(EXPECT_FAILURE)
    message(STATUS "failed, as it should")
    return()
  endif()
  message(FATAL_ERROR "the renders differ from ${reference} by more than their noise explains; "
                      "see ${work_dir}/diff.png and ${work_dir}/z.png")
endif()
if(NOT code EQUAL 0 AND NOT code EQUAL 1)
  message(FATAL_ERROR "rtiow diff could not compare (exit ${code})")
endif()
if(EXPECT_FAILURE)
  message(FATAL_ERROR "the comparison passed but was expected to fail: it cannot see this "
                      "change")
endif()
