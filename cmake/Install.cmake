# `cmake --install build --prefix P`: the rtiow executable (with the plot scripts it runs, in
# share/rtiow/),
# the core as a static library with its headers and image backend, and a CMake package, so
# that a C++ project can find_package(rtiow) and link rtiow::rtiow, or declare image tests of
# its scenes with rtiow_add_image_test (cmake/RtiowImageTest.cmake).
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set_target_properties(rtiow_core PROPERTIES EXPORT_NAME rtiow OUTPUT_NAME rtiow)
install(TARGETS rtiow RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(FILES core/measure/bench_plot.py core/measure/accuracy_plot.py
        DESTINATION ${CMAKE_INSTALL_DATADIR}/rtiow)
install(TARGETS rtiow_core EXPORT rtiowTargets ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
# The image backend: the rtiow executable loads the shared one from lib/ beside its bin/ when
# it reads or writes an image. A program that links rtiow::rtiow writes PNG with rtiow's own
# encoder and links no OpenImageIO; one that wants the other formats (EXR, JPEG, TIFF, ...)
# links rtiow::image_io too, the static backend, so it runs wherever it is installed and
# wherever the prefix moves, at the cost of OpenImageIO's libraries and start-up.
install(TARGETS rtiow_image_io LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
set_target_properties(rtiow_image_io_static PROPERTIES EXPORT_NAME image_io
                                                       OUTPUT_NAME rtiow_image_io)
install(TARGETS rtiow_image_io_static EXPORT rtiowTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
foreach(oiio_target OpenImageIO OpenImageIO_Util)
  get_target_property(oiio_file OpenImageIO::${oiio_target} LOCATION)
  set_property(TARGET rtiow_image_io_static APPEND PROPERTY INTERFACE_LINK_LIBRARIES
               "$<INSTALL_INTERFACE:${oiio_file}>")
endforeach()
# The backend's entry point, which the core references weakly, pulls it out of its archive.
set_property(TARGET rtiow_image_io_static APPEND PROPERTY INTERFACE_LINK_OPTIONS
             "$<INSTALL_INTERFACE:LINKER:--undefined=rtiow_image_backend>")
# The public API (cmake/InstallPublicHeaders.cmake): core/rtiow.h and what it includes, as
# include/rtiow/..., included as <rtiow/rtiow.h>.
set(rtiow_public_headers ${CMAKE_CURRENT_BINARY_DIR}/public-headers)
install(CODE "set(RTIOW_SOURCE_DIR \"${PROJECT_SOURCE_DIR}\")
set(RTIOW_STAGING_DIR \"${rtiow_public_headers}\")
include(\"${PROJECT_SOURCE_DIR}/cmake/InstallPublicHeaders.cmake\")")
install(DIRECTORY ${rtiow_public_headers}/rtiow DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})

# The manual as the source tree lays it out, so that its links hold: README.md, the docs/ pages
# --help cites as docs/<page> (with the figures and measurements they link) and the examples
# the README links.
install(FILES README.md DESTINATION ${CMAKE_INSTALL_DOCDIR})
install(DIRECTORY docs/ DESTINATION ${CMAKE_INSTALL_DOCDIR}/docs)
install(DIRECTORY examples/ DESTINATION ${CMAKE_INSTALL_DOCDIR}/examples)

set(rtiow_cmake_dir ${CMAKE_INSTALL_LIBDIR}/cmake/rtiow)
install(EXPORT rtiowTargets NAMESPACE rtiow:: DESTINATION ${rtiow_cmake_dir})
configure_package_config_file(cmake/rtiowConfig.cmake.in
                              ${CMAKE_CURRENT_BINARY_DIR}/rtiowConfig.cmake
                              INSTALL_DESTINATION ${rtiow_cmake_dir}
                              PATH_VARS CMAKE_INSTALL_BINDIR)
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/rtiowConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/rtiowConfig.cmake
              ${CMAKE_CURRENT_BINARY_DIR}/rtiowConfigVersion.cmake
              cmake/RtiowImageTest.cmake cmake/RtiowImageTestRun.cmake
        DESTINATION ${rtiow_cmake_dir})
