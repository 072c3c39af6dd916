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
rtiow_require(CLI11 libcli11-dev)
rtiow_require(nlohmann_json nlohmann-json3-dev)
find_package(Threads REQUIRED)

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
