# The library as a user gets it: install this build into a scratch prefix, configure and build
# examples/spheres against it with find_package(rtiow), run it, and check it wrote its image.
# Run by CTest as: cmake -DBUILD_DIR=... -DSOURCE_DIR=... -DWORK_DIR=... -P install_example.cmake
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT code EQUAL 0)
    message(FATAL_ERROR "failed (${code}): ${ARGN}\n${out}\n${err}")
  endif()
endfunction()

file(REMOVE_RECURSE ${WORK_DIR})
set(prefix ${WORK_DIR}/prefix)
run(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})
foreach(installed bin/rtiow lib/librtiow.a lib/librtiow_image_io.so include/rtiow/core/rtiow.h
                  include/rtiow/materials/material.h lib/cmake/rtiow/rtiowConfig.cmake)
  if(NOT EXISTS ${prefix}/${installed})
    message(FATAL_ERROR "not installed: ${installed}")
  endif()
endforeach()
# The installed program finds its image backend in lib/ beside its bin/.
run(${prefix}/bin/rtiow render -q --scene cover --width 16 --height 9 --spp 1
    -o ${WORK_DIR}/cover.png)
if(NOT EXISTS ${WORK_DIR}/cover.png)
  message(FATAL_ERROR "the installed rtiow wrote no image")
endif()
run(${CMAKE_COMMAND} -S ${SOURCE_DIR}/examples/spheres -B ${WORK_DIR}/build
    -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_BUILD_TYPE=Release)
run(${CMAKE_COMMAND} --build ${WORK_DIR}/build)
run(${WORK_DIR}/build/spheres ${WORK_DIR}/three.png)
file(SIZE ${WORK_DIR}/three.png size)
if(size LESS 10000)
  message(FATAL_ERROR "the example's image is only ${size} bytes")
endif()
message(STATUS "installed rtiow built and ran the example: three.png, ${size} bytes")
