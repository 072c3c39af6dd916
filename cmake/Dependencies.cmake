# Every dependency comes from a Debian package and is found through its CMake config.
# cmake/install-deps.sh installs them; the hints below name the package to install.
macro(rtiow_require package debian_package)
  find_package(${package} ${ARGN} QUIET)
  if(NOT ${package}_FOUND)
    message(FATAL_ERROR "rtiow needs ${package}: install the Debian package '${debian_package}' "
                        "(or run: bash cmake/install-deps.sh)")
  endif()
endmacro()

rtiow_require(embree libembree-dev 3)
rtiow_require(TBB libtbb-dev)
rtiow_require(OpenImageIO libopenimageio-dev)
# libpng writes PNG, the default output, without loading the image library (core/io/png_encoder.h).
rtiow_require(PNG libpng-dev)
rtiow_require(CLI11 libcli11-dev)
rtiow_require(nlohmann_json nlohmann-json3-dev)
# RapidJSON reads scene files (its SAX reader is 2.7x faster than nlohmann's on a big scene);
# nlohmann-json writes JSON. Debian's RapidJSON config gives directories (RAPIDJSON_INCLUDE_DIRS),
# not a target: the core uses them privately, so the installed package does not need it.
rtiow_require(RapidJSON rapidjson-dev)
# Eigen solves the denoiser's per-pixel least squares (core/denoise/feature_regression.cpp).
rtiow_require(Eigen3 libeigen3-dev 3.3 NO_MODULE)
find_package(Threads REQUIRED)

# MPI is optional: ON when Debian's OpenMPI (libopenmpi-dev) is installed, unless turned off.
set(RTIOW_MPI AUTO CACHE STRING "Build with MPI: AUTO (if found), ON or OFF")
if(NOT RTIOW_MPI STREQUAL "OFF")
  find_package(MPI COMPONENTS CXX QUIET)
  if(MPI_CXX_FOUND)
    set(RTIOW_MPI ON)
  elseif(RTIOW_MPI STREQUAL "ON")
    message(FATAL_ERROR "RTIOW_MPI=ON but MPI was not found: install libopenmpi-dev")
  else()
    set(RTIOW_MPI OFF)
  endif()
endif()
message(STATUS "rtiow: MPI ${RTIOW_MPI}")

# The Python module: Debian's Python with its development files (python3-dev) and numpy
# (python3-numpy), and Debian's pybind11 (pybind11-dev). Debian's /usr/bin/python3 is preferred
# to another python3 first on PATH (a pyenv's has no numpy of Debian's); -DPython3_EXECUTABLE=...
# builds for another.
set(RTIOW_PYTHON_FOUND OFF)
if(RTIOW_PYTHON)
  if(NOT DEFINED Python3_EXECUTABLE AND EXISTS /usr/bin/python3)
    set(Python3_EXECUTABLE /usr/bin/python3)
  endif()
  find_package(Python3 COMPONENTS Interpreter Development.Module QUIET)
  if(Python3_FOUND)
    find_package(pybind11 CONFIG QUIET)
  endif()
  if(Python3_FOUND AND pybind11_FOUND)
    set(RTIOW_PYTHON_FOUND ON)
  endif()
endif()
message(STATUS "rtiow: Python module ${RTIOW_PYTHON_FOUND}")

# Debian 12's OpenImageIO config lists /usr/include/opencv4 among its include directories
# although nothing we use needs OpenCV; drop include directories that do not exist rather
# than pull in libopencv-dev.
get_target_property(_oiio_includes OpenImageIO::OpenImageIO INTERFACE_INCLUDE_DIRECTORIES)
set(_oiio_existing_includes "")
foreach(_dir IN LISTS _oiio_includes)
  if(EXISTS "${_dir}")
    list(APPEND _oiio_existing_includes "${_dir}")
  endif()
endforeach()
set_target_properties(OpenImageIO::OpenImageIO PROPERTIES
                      INTERFACE_INCLUDE_DIRECTORIES "${_oiio_existing_includes}")
