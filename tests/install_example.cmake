# The library as a user gets it: install this build into a scratch prefix, configure and build
# examples/spheres against it with find_package(rtiow), run it, and check it wrote its image;
# then run examples/image_tests (rtiow_add_image_test) against the install: make its
# references, compare, and see its guard fail as it should.
# Run by CTest as:
#   cmake -DBUILD_DIR=... -DSOURCE_DIR=... -DWORK_DIR=... -DCTEST=... -P install_example.cmake
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT code EQUAL 0)
    message(FATAL_ERROR "failed (${code}): ${ARGN}\n${out}\n${err}")
  endif()
endfunction()

file(REMOVE_RECURSE ${WORK_DIR})
set(prefix ${WORK_DIR}/prefix)
run(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})
foreach(installed bin/rtiow lib/librtiow.a lib/librtiow_image_io.so include/rtiow/rtiow.h
                  include/rtiow/materials/material.h lib/cmake/rtiow/rtiowConfig.cmake
                  lib/cmake/rtiow/RtiowImageTest.cmake lib/cmake/rtiow/RtiowImageTestRun.cmake
                  share/doc/rtiow/README.md share/doc/rtiow/docs/usage.md
                  share/doc/rtiow/docs/scene-format.md share/doc/rtiow/docs/diff.md
                  share/rtiow/bench_plot.py share/rtiow/accuracy_plot.py)
  if(NOT EXISTS ${prefix}/${installed})
    message(FATAL_ERROR "not installed: ${installed}")
  endif()
endforeach()
if(EXISTS ${prefix}/bin/bench_plot.py OR EXISTS ${prefix}/bin/accuracy_plot.py)
  message(FATAL_ERROR "a plot script was installed among the programs in bin/")
endif()
# Every relative link of the installed manual reaches a file that was installed.
file(GLOB_RECURSE pages ${prefix}/share/doc/rtiow/*.md)
set(links 0)
foreach(page ${pages})
  file(READ ${page} text)
  get_filename_component(page_dir ${page} DIRECTORY)
  # Brackets and semicolons would bend CMake's lists: a link's "](" is matched as ">(".
  string(REPLACE "[" "<" text "${text}")
  string(REPLACE "]" ">" text "${text}")
  string(REPLACE ";" "," text "${text}")
  string(REGEX MATCHALL ">\\([^)#:][^):]*\\)" found "${text}")
  foreach(link ${found})
    string(REGEX REPLACE "^>\\(([^)#]*).*$" "\\1" target "${link}")
    if(NOT EXISTS ${page_dir}/${target})
      message(FATAL_ERROR "the installed ${page} links ${target}, which was not installed")
    endif()
    math(EXPR links "${links} + 1")
  endforeach()
endforeach()
if(links LESS 30)
  message(FATAL_ERROR "only ${links} links found in the installed manual: the check missed them")
endif()
message(STATUS "the installed manual's ${links} relative links all reach installed files")
# The installed program finds its image backend in lib/ beside its bin/.
run(${prefix}/bin/rtiow render -q --scene cover --width 16 --height 9 --spp 1
    -o ${WORK_DIR}/cover.png)
if(NOT EXISTS ${WORK_DIR}/cover.png)
  message(FATAL_ERROR "the installed rtiow wrote no image")
endif()
# The installed Python module (where it is built): Debian's Python finds it in the prefix's
# lib/python3/dist-packages, and it finds the image backend in the prefix's lib/ (an EXR).
if(PYTHON)
  run(${CMAKE_COMMAND} -E env PYTHONPATH=${prefix}/lib/python3/dist-packages
      PYTHONDONTWRITEBYTECODE=1 ${PYTHON} -c
      # One expression: a semicolon would split the argument in CMake's list.
      "__import__('rtiow').render(__import__('rtiow').builtin_scene(), width=16, spp=1).write('${WORK_DIR}/python.exr')")
  if(NOT EXISTS ${WORK_DIR}/python.exr)
    message(FATAL_ERROR "the installed Python module wrote no image")
  endif()
  message(STATUS "the installed Python module rendered and wrote an EXR")
endif()
# The example sets no C++ standard (the target carries cxx_std_20), and its find_package(rtiow)
# must configure without a warning (OpenImageIO's package, which warns about a Python module of
# Imath on Debian, is not looked for).
execute_process(COMMAND ${CMAKE_COMMAND} -S ${SOURCE_DIR}/examples/spheres -B ${WORK_DIR}/build
                        -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_BUILD_TYPE=Release
                RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT code EQUAL 0 OR err MATCHES "Warning|warning|PyImath")
  message(FATAL_ERROR "configuring the example against the install (${code}):\n${out}\n${err}")
endif()
run(${CMAKE_COMMAND} --build ${WORK_DIR}/build)
run(${WORK_DIR}/build/spheres ${WORK_DIR}/three.png)
file(SIZE ${WORK_DIR}/three.png size)
if(size LESS 10000)
  message(FATAL_ERROR "the example's image is only ${size} bytes")
endif()
message(STATUS "installed rtiow built and ran the example: three.png, ${size} bytes")

# A program that writes PNG links no OpenImageIO library (it would load some 260 shared
# libraries); asked for EXR it says what to link. The one that links rtiow::image_io writes EXR.
function(shared_libraries program out)
  execute_process(COMMAND ldd ${program} RESULT_VARIABLE code OUTPUT_VARIABLE listed)
  if(NOT code EQUAL 0)
    message(FATAL_ERROR "ldd ${program} failed (${code})")
  endif()
  string(REGEX MATCHALL "[^\n]*=>[^\n]*" libraries "${listed}")
  set(${out} "${libraries}" PARENT_SCOPE)
endfunction()
shared_libraries(${WORK_DIR}/build/spheres png_only)
shared_libraries(${WORK_DIR}/build/spheres_any_format any_format)
list(LENGTH png_only png_only_count)
list(LENGTH any_format any_format_count)
list(FILTER png_only INCLUDE REGEX "OpenImageIO")
list(FILTER any_format INCLUDE REGEX "OpenImageIO")
list(LENGTH png_only png_only_oiio)
list(LENGTH any_format any_format_oiio)
message(STATUS "shared libraries: ${png_only_count} writing PNG (${png_only_oiio} of "
               "OpenImageIO), ${any_format_count} with rtiow::image_io (${any_format_oiio})")
if(NOT png_only_oiio EQUAL 0 OR any_format_oiio EQUAL 0)
  message(FATAL_ERROR "a PNG-only program links ${png_only_oiio} OpenImageIO libraries, one "
                      "with rtiow::image_io ${any_format_oiio}")
endif()
execute_process(COMMAND ${WORK_DIR}/build/spheres ${WORK_DIR}/three.exr RESULT_VARIABLE code
                OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(code EQUAL 0 OR NOT err MATCHES "rtiow::image_io" OR EXISTS ${WORK_DIR}/three.exr)
  message(FATAL_ERROR "a PNG-only program asked for EXR (${code}) should say to link "
                      "rtiow::image_io:\n${out}${err}")
endif()
run(${WORK_DIR}/build/spheres_any_format ${WORK_DIR}/three.exr)

# A render stopped and resumed from its checkpoint, and one in two part files merged, through
# the library alone (examples/render_farm): the program checks both against one render of all
# the samples, bit for bit, and fails otherwise.
run(${CMAKE_COMMAND} -S ${SOURCE_DIR}/examples/render_farm -B ${WORK_DIR}/farm-build
    -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_BUILD_TYPE=Release)
run(${CMAKE_COMMAND} --build ${WORK_DIR}/farm-build)
execute_process(COMMAND ${WORK_DIR}/farm-build/render_farm ${WORK_DIR} RESULT_VARIABLE code
                OUTPUT_VARIABLE out ERROR_VARIABLE err)
string(REGEX MATCHALL "identical to one render" identical "${out}")
list(LENGTH identical identical_count)
if(NOT code EQUAL 0 OR NOT identical_count EQUAL 2 OR NOT EXISTS ${WORK_DIR}/merged.exr)
  message(FATAL_ERROR "the render farm example (${code}):\n${out}${err}")
endif()
message(STATUS "${out}")

# Only the public API is installed: the headers core/rtiow.h includes, under include/rtiow,
# including one another as "rtiow/..." and needing nothing the package does not find.
file(GLOB_RECURSE headers RELATIVE ${prefix}/include ${prefix}/include/*)
list(LENGTH headers header_count)
message(STATUS "installed headers: ${header_count}")
foreach(header ${headers})
  if(NOT header MATCHES "^rtiow/")
    message(FATAL_ERROR "installed outside include/rtiow: ${header}")
  endif()
  file(STRINGS ${prefix}/include/${header} includes REGEX "#[ \t]*include[ \t]*\"")
  foreach(line ${includes})
    if(NOT line MATCHES "\"rtiow/")
      message(FATAL_ERROR "installed ${header} includes a header outside the API: ${line}")
    endif()
    string(REGEX REPLACE ".*\"([^\"]+)\".*" "\\1" included "${line}")
    if(NOT EXISTS ${prefix}/include/${included})
      message(FATAL_ERROR "installed ${header} includes ${included}, not installed")
    endif()
    list(APPEND reached ${included})
  endforeach()
  file(STRINGS ${prefix}/include/${header} internal REGEX "rapidjson|nlohmann")
  if(internal)
    message(FATAL_ERROR "installed ${header} needs the core's internals: ${internal}")
  endif()
endforeach()
# Each installed header but the umbrella is reached from another: nothing internal rides along.
list(APPEND reached rtiow/rtiow.h)
list(REMOVE_ITEM headers ${reached})
if(headers)
  message(FATAL_ERROR "installed but not part of <rtiow/rtiow.h>: ${headers}")
endif()

# A program built against the install keeps working when the prefix moves (the image
# backend is linked in): move it, run the example again, move it back.
file(REMOVE ${WORK_DIR}/three.exr)
file(RENAME ${prefix} ${WORK_DIR}/moved)
execute_process(COMMAND ${WORK_DIR}/build/spheres_any_format ${WORK_DIR}/three.exr
                RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
file(RENAME ${WORK_DIR}/moved ${prefix})
if(NOT code EQUAL 0 OR NOT EXISTS ${WORK_DIR}/three.exr)
  message(FATAL_ERROR "the example failed once the prefix moved (${code}):\n${out}${err}")
endif()
message(STATUS "the example ran with its install prefix moved")

# The image tests, copied out of the source tree so their references are written here.
file(COPY ${SOURCE_DIR}/examples/image_tests DESTINATION ${WORK_DIR})
set(tests_source ${WORK_DIR}/image_tests)
run(${CMAKE_COMMAND} -S ${tests_source} -B ${WORK_DIR}/image_tests_build
    -DCMAKE_PREFIX_PATH=${prefix})
# Without its reference a test fails and says the command that makes it, with its own name.
execute_process(COMMAND ${CTEST} --test-dir ${WORK_DIR}/image_tests_build -R "^three_spheres$"
                        --output-on-failure
                RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(code EQUAL 0 OR NOT out MATCHES "RTIOW_UPDATE_REFERENCES=1 ctest -R '\\^three_spheres\\$'")
  message(FATAL_ERROR "an image test without its reference did not say how to make it:\n"
                      "${out}${err}")
endif()
run(${CMAKE_COMMAND} -E env RTIOW_UPDATE_REFERENCES=1
    ${CTEST} --test-dir ${WORK_DIR}/image_tests_build --output-on-failure)
if(NOT EXISTS ${tests_source}/references/three-spheres.exr)
  message(FATAL_ERROR "the image test wrote no reference")
endif()
execute_process(COMMAND ${CTEST} --test-dir ${WORK_DIR}/image_tests_build -V
                RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT code EQUAL 0 OR NOT out MATCHES "PASS" OR NOT out MATCHES "failed, as it should")
  message(FATAL_ERROR "the installed image tests did not pass and fail as they should:\n"
                      "${out}${err}")
endif()
message(STATUS "the installed rtiow_add_image_test made references, passed, and failed the "
               "moved camera")
