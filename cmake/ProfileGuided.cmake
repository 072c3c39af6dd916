# Profile-guided and link-time optimisation (GCC): before the renderer is compiled, an
# instrumented copy of rtiow_core, the renderer, is built in build/pgo/build with a small
# program that renders a few jobs through it (cmake/profile_training.cpp); rtiow_core is then
# compiled with that profile, and the rtiow program links it with -flto. Only the core is
# compiled twice, the second time being what a profile is for: the command line around it,
# whose profile nothing would use, and the image backend are compiled once. The
# core's objects are fat, so the tests and library users link them as ordinary objects.
# Neither changes a pixel (floating-point semantics are untouched: the same -ffp-contract=off,
# no fast-math); together they made the render loop about 6% faster (docs/performance.md; not
# resolvable on a noisier machine on 11-28). A source change runs the training again. They add
# about 40 s to a fresh build;
# -DRTIOW_PGO=OFF builds without either.
#
# RTIOW_PGO_GENERATE is the nested build's own setting: compile instrumented, writing the
# profile to that directory.

option(RTIOW_PGO "Compile the renderer with a profile of its own renders (GCC only)" ON)
set(RTIOW_PGO_GENERATE "" CACHE PATH "Internal: compile instrumented, profiles to this directory")
mark_as_advanced(RTIOW_PGO_GENERATE)

set(RTIOW_PGO_ACTIVE OFF)
if(RTIOW_PGO_GENERATE)
  # Object names in the profile are relative to the build tree, so the instrumented tree's
  # profile matches the optimised tree's objects.
  add_compile_options(-fprofile-generate=${RTIOW_PGO_GENERATE}
                      -fprofile-prefix-path=${CMAKE_BINARY_DIR} -fprofile-update=prefer-atomic)
  add_link_options(-fprofile-generate=${RTIOW_PGO_GENERATE})
elseif(RTIOW_PGO AND CMAKE_CXX_COMPILER_ID STREQUAL "GNU"
       AND CMAKE_BUILD_TYPE MATCHES "^(Release|RelWithDebInfo)$")
  set(RTIOW_PGO_ACTIVE ON)
  set(RTIOW_PGO_DIR ${CMAKE_BINARY_DIR}/pgo)
  set(RTIOW_PGO_STAMP ${RTIOW_PGO_DIR}/profile.stamp)
  cmake_host_system_information(RESULT rtiow_pgo_jobs QUERY NUMBER_OF_LOGICAL_CORES)
  file(GLOB_RECURSE rtiow_pgo_sources CONFIGURE_DEPENDS
       ${PROJECT_SOURCE_DIR}/core/*.cpp ${PROJECT_SOURCE_DIR}/core/*.h
       ${PROJECT_SOURCE_DIR}/materials/*.h)
  add_custom_command(
    OUTPUT ${RTIOW_PGO_STAMP}
    COMMAND ${CMAKE_COMMAND} -E rm -rf ${RTIOW_PGO_DIR}/data
    COMMAND ${CMAKE_COMMAND} -S ${PROJECT_SOURCE_DIR} -B ${RTIOW_PGO_DIR}/build
            -DCMAKE_BUILD_TYPE=${CMAKE_BUILD_TYPE} -DCMAKE_CXX_COMPILER=${CMAKE_CXX_COMPILER}
            -DRTIOW_NATIVE=${RTIOW_NATIVE} -DRTIOW_MPI=${RTIOW_MPI} -DRTIOW_PGO=OFF
            -DRTIOW_BUILD_TESTS=OFF -DRTIOW_PGO_GENERATE=${RTIOW_PGO_DIR}/data
    # Its own make, not a part of the outer one's job slots (so none of make's warnings).
    COMMAND ${CMAKE_COMMAND} -E env --unset=MAKEFLAGS --unset=MFLAGS
            ${CMAKE_COMMAND} --build ${RTIOW_PGO_DIR}/build --target rtiow_profile_training -j ${rtiow_pgo_jobs}
    COMMAND ${RTIOW_PGO_DIR}/build/bin/rtiow_profile_training ${RTIOW_PGO_DIR}
    COMMAND ${CMAKE_COMMAND} -E touch ${RTIOW_PGO_STAMP}
    DEPENDS ${rtiow_pgo_sources} ${PROJECT_SOURCE_DIR}/cmake/profile_training.cpp
    COMMENT "Profiling an instrumented rtiow for profile-guided optimisation (-DRTIOW_PGO=OFF skips)"
    VERBATIM)
  add_custom_target(rtiow_profile DEPENDS ${RTIOW_PGO_STAMP})
endif()

# rtiow_use_profile(target): compile the target with the profile, after it is made. An object
# whose source (or header) changed is compiled again after the training ran again on the new
# code; an unchanged one keeps the profile it was compiled with, which still describes it.
function(rtiow_use_profile target)
  if(NOT RTIOW_PGO_ACTIVE)
    return()
  endif()
  add_dependencies(${target} rtiow_profile)
  # -fprofile-partial-training: code the training did not run is compiled as without a
  # profile, not for size. The warnings would name every file the training never reached.
  # -ffat-lto-objects: the program links the core with -flto (rtiow_link_time_optimise), every
  # other user links the ordinary code beside it.
  target_compile_options(${target} PRIVATE -fprofile-use=${RTIOW_PGO_DIR}/data
                         -fprofile-prefix-path=${CMAKE_BINARY_DIR} -fprofile-partial-training
                         -Wno-missing-profile -Wno-coverage-mismatch -flto=auto -ffat-lto-objects)
endfunction()

# rtiow_link_time_optimise(target): link the target with -flto, so the profiled core's code is
# optimised across its files and into the program (measured without a profile, -flto alone
# gained nothing).
function(rtiow_link_time_optimise target)
  if(RTIOW_PGO_ACTIVE)
    target_link_options(${target} PRIVATE -flto=auto)
  endif()
endfunction()
