# Sanitizer builds of the core and of the unit and render tests, run as ordinary CTest tests
# (label `sanitize`): AddressSanitizer with UndefinedBehaviorSanitizer, and ThreadSanitizer
# for the parallel sample loop. They share nothing with the Release targets but the sources.

set(RTIOW_SANITIZER_FLAGS_asan -fsanitize=address,undefined -fno-sanitize-recover=all
                               -fno-omit-frame-pointer -g -O1)
set(RTIOW_SANITIZER_FLAGS_tsan -fsanitize=thread -g -O1)

# rtiow_add_sanitized_test(kind name SOURCES ...): `name`_`kind`, linked against a sanitized core.
function(rtiow_add_sanitized_test kind name)
  cmake_parse_arguments(ARG "" "" "SOURCES" ${ARGN})
  if(NOT TARGET rtiow_core_${kind})
    rtiow_add_core_library(rtiow_core_${kind})
    target_compile_options(rtiow_core_${kind} PRIVATE ${RTIOW_SANITIZER_FLAGS_${kind}})
    target_link_options(rtiow_core_${kind} PUBLIC ${RTIOW_SANITIZER_FLAGS_${kind}})
    if(kind STREQUAL "tsan")
      # The instruction-set choice is an ifunc, resolved while the program loads, before
      # ThreadSanitizer's runtime is up (it crashes there): one instruction set under TSan.
      target_compile_definitions(rtiow_core_${kind} PUBLIC RTIOW_NO_DISPATCH)
    endif()
  endif()
  set(target ${name}_${kind})
  add_executable(${target} ${ARG_SOURCES})
  target_include_directories(${target} PRIVATE ${PROJECT_SOURCE_DIR})
  target_link_libraries(${target} PRIVATE rtiow_core_${kind} OpenImageIO::OpenImageIO
                                          GTest::gtest_main)
  target_compile_options(${target} PRIVATE ${RTIOW_SANITIZER_FLAGS_${kind}})
  target_compile_definitions(${target} PRIVATE RTIOW_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
                                                RTIOW_TEST_OUTPUT_DIR="${CMAKE_CURRENT_BINARY_DIR}/output")
  rtiow_set_warnings(${target})
  rtiow_set_codegen(${target})
  # Brief: only a failing test's lines and the sanitizer's report, so a failure shows in the
  # tail of a long CI log rather than among some hundred passing tests' lines.
  # ThreadSanitizer looks for races; the suite's longest tests under it are left to ASan where
  # their threads are others' already: the single-threaded float printing round trip (2 million
  # values, 21 s), the adaptive modes resumed (37 s: the render loop's rounds, which other
  # tests run under TSan) and the scene reader's refusals (25 s: the pipeline, which the
  # accepted-scene tests run).
  set(filter "")
  if(kind STREQUAL "tsan")
    set(filter "--gtest_filter=-JsonFloat.*:Checkpoint.AdaptiveModesResumeToTheSameBits:SceneInRuns.RefusesWhatTheOnePieceParseRefuses")
  endif()
  add_test(NAME ${target} COMMAND ${target} --gtest_brief=1 ${filter})
  set_tests_properties(${target} PROPERTIES
    LABELS sanitize
    ENVIRONMENT "ASAN_OPTIONS=detect_leaks=1:abort_on_error=0;UBSAN_OPTIONS=print_stacktrace=1;TSAN_OPTIONS=halt_on_error=1:second_deadlock_stack=1:suppressions=${PROJECT_SOURCE_DIR}/tests/tsan.supp")
endfunction()
