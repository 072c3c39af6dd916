# Image tests for your own scenes: each renders a scene at small settings with several seeds
# and compares the renders with a stored reference through `rtiow diff` (the several-seed,
# noise-aware comparison: a difference fails only where the renders' own spread cannot
# explain it; see docs/diff.md). find_package(rtiow) includes this file; in rtiow's own tree
# it is included by tests/CMakeLists.txt.
#
#   rtiow_add_image_test(<name>
#     SCENE <file.json> | BUILTIN <scene name>
#     REFERENCE <file.exr>          # made by the test itself when references are updated
#     [WIDTH <px>] [HEIGHT <px>]    # default: the scene's, so give at least WIDTH
#     [SPP <n>]                     # per render, default 16
#     [SEEDS <k>]                   # renders, seeds 1..k, default 8 (at least 2)
#     [REFERENCE_SPP <n>]           # default 1024, rendered with seed 0
#     [RENDER_ARGS <arg>...]        # more `rtiow render` options (--depth, --sampler, ...)
#     [DIFF_ARGS <arg>...]          # more `rtiow diff` options (--alpha, --block)
#     [LABELS <label>...]           # CTest labels, default "image"
#     [EXPECT_FAILURE]              # pass only if the comparison fails (a guard's guard)
#     [RTIOW <executable>])         # default: the rtiow target, else the installed one
#
# Make or remake references with RTIOW_UPDATE_REFERENCES=1 in the environment:
#   RTIOW_UPDATE_REFERENCES=1 ctest -L image
# Each failing test leaves <name>/diff.png (|mean of renders - reference|) and <name>/z.png
# (the blocks' t-scores: red brighter, blue darker) in the build tree, and prints both paths.

function(rtiow_add_image_test name)
  cmake_parse_arguments(
    PARSE_ARGV 1 ARG "EXPECT_FAILURE"
    "SCENE;BUILTIN;REFERENCE;WIDTH;HEIGHT;SPP;SEEDS;REFERENCE_SPP;RTIOW"
    "RENDER_ARGS;DIFF_ARGS;LABELS")
  if(ARG_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR "rtiow_add_image_test(${name}): unknown arguments ${ARG_UNPARSED_ARGUMENTS}")
  endif()
  if(NOT ARG_REFERENCE)
    message(FATAL_ERROR "rtiow_add_image_test(${name}): REFERENCE is required")
  endif()
  if(ARG_SCENE AND ARG_BUILTIN OR NOT (ARG_SCENE OR ARG_BUILTIN))
    message(FATAL_ERROR "rtiow_add_image_test(${name}): give one of SCENE <file> or BUILTIN <name>")
  endif()
  set(default_SPP 16)
  set(default_SEEDS 8)
  set(default_REFERENCE_SPP 1024)
  foreach(option SPP SEEDS REFERENCE_SPP)
    if(NOT DEFINED ARG_${option})
      set(ARG_${option} ${default_${option}})
    endif()
  endforeach()
  if(ARG_SEEDS LESS 2)
    message(FATAL_ERROR "rtiow_add_image_test(${name}): SEEDS must be at least 2")
  endif()
  if(NOT ARG_LABELS)
    set(ARG_LABELS image)
  endif()
  if(NOT ARG_RTIOW)
    if(TARGET rtiow)
      set(ARG_RTIOW $<TARGET_FILE:rtiow>)
    elseif(RTIOW_EXECUTABLE)
      set(ARG_RTIOW ${RTIOW_EXECUTABLE})
    else()
      find_program(RTIOW_EXECUTABLE rtiow REQUIRED)
      set(ARG_RTIOW ${RTIOW_EXECUTABLE})
    endif()
  endif()

  # The render's arguments, shared by the tests' and the reference's renders.
  if(ARG_SCENE)
    get_filename_component(scene ${ARG_SCENE} ABSOLUTE)
    set(render_args ${scene})
  else()
    set(render_args --scene ${ARG_BUILTIN})
  endif()
  if(ARG_WIDTH)
    list(APPEND render_args --width ${ARG_WIDTH})
  endif()
  if(ARG_HEIGHT)
    list(APPEND render_args --height ${ARG_HEIGHT})
  endif()
  list(APPEND render_args ${ARG_RENDER_ARGS})
  get_filename_component(reference ${ARG_REFERENCE} ABSOLUTE)

  # Lists go through a generated file: a semicolon on a test's command line splits it.
  set(work_dir ${CMAKE_CURRENT_BINARY_DIR}/rtiow-image-tests/${name})
  set(settings ${CMAKE_CURRENT_BINARY_DIR}/rtiow-image-tests/${name}.cmake)
  set(content "")
  set(TEST_NAME ${name})
  foreach(variable TEST_NAME RTIOW reference render_args work_dir SPP SEEDS REFERENCE_SPP
                   DIFF_ARGS EXPECT_FAILURE)
    if(DEFINED ARG_${variable})
      set(value "${ARG_${variable}}")
    else()
      set(value "${${variable}}")
    endif()
    string(APPEND content "set(${variable} [==[${value}]==])\n")
  endforeach()
  file(GENERATE OUTPUT ${settings} CONTENT "${content}")
  add_test(NAME ${name}
           COMMAND ${CMAKE_COMMAND} -DSETTINGS=${settings} -P ${CMAKE_CURRENT_FUNCTION_LIST_DIR}/RtiowImageTestRun.cmake)
  set_tests_properties(${name} PROPERTIES LABELS "${ARG_LABELS}")
endfunction()
