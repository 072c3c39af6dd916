# `cmake --install build --prefix P`: the rtiow executable (with the plot scripts it runs),
# the core as a static library with its headers, and a CMake package, so that a C++ project
# can find_package(rtiow) and link rtiow::rtiow.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set_target_properties(rtiow_core PROPERTIES EXPORT_NAME rtiow OUTPUT_NAME rtiow)
install(TARGETS rtiow RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(FILES app/bench_plot.py app/accuracy_plot.py DESTINATION ${CMAKE_INSTALL_BINDIR})
install(TARGETS rtiow_core EXPORT rtiowTargets ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(DIRECTORY core materials DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/rtiow
        FILES_MATCHING PATTERN "*.h")

set(rtiow_cmake_dir ${CMAKE_INSTALL_LIBDIR}/cmake/rtiow)
install(EXPORT rtiowTargets NAMESPACE rtiow:: DESTINATION ${rtiow_cmake_dir})
configure_package_config_file(cmake/rtiowConfig.cmake.in
                              ${CMAKE_CURRENT_BINARY_DIR}/rtiowConfig.cmake
                              INSTALL_DESTINATION ${rtiow_cmake_dir})
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/rtiowConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/rtiowConfig.cmake
              ${CMAKE_CURRENT_BINARY_DIR}/rtiowConfigVersion.cmake
        DESTINATION ${rtiow_cmake_dir})
