# cmake --install: the program, the libraries with their headers, and a package config, so that
# another project's find_package(tcpmsim) gives it tcpmsim::tcpmsim_identification (and the
# layers below it: tcpmsim_engine, _components, _analysis, _sweep).
include(CMakePackageConfigHelpers)
set(TCPMSIM_LIBRARIES tcpmsim_engine tcpmsim_components tcpmsim_analysis tcpmsim_sweep
                      tcpmsim_identification)
set(TCPMSIM_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/tcpmsim)

install(TARGETS tcpmsim RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
if(NOT TCPMSIM_PYTHON)  # with Python, python/CMakeLists.txt installs it with its package
  install(PROGRAMS tools/tcpmsim-plot DESTINATION ${CMAKE_INSTALL_BINDIR})
endif()
install(TARGETS ${TCPMSIM_LIBRARIES} EXPORT tcpmsimTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
# The headers keep the source tree's layout: #include "sim/scenario.h" from include/tcpmsim.
install(DIRECTORY sim signals models controllers kinds analysis sweep identification
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/tcpmsim
        FILES_MATCHING PATTERN "*.h")
install(FILES ${CMAKE_BINARY_DIR}/generated/tcpmsim/version.h
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/tcpmsim/tcpmsim)
install(EXPORT tcpmsimTargets NAMESPACE tcpmsim:: DESTINATION ${TCPMSIM_CMAKE_DIR})

set(TCPMSIM_WITH_MPI ${MPI_CXX_FOUND})
configure_package_config_file(cmake/tcpmsimConfig.cmake.in
                              ${CMAKE_BINARY_DIR}/cmake/tcpmsimConfig.cmake
                              INSTALL_DESTINATION ${TCPMSIM_CMAKE_DIR})
write_basic_package_version_file(${CMAKE_BINARY_DIR}/cmake/tcpmsimConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_BINARY_DIR}/cmake/tcpmsimConfig.cmake
              ${CMAKE_BINARY_DIR}/cmake/tcpmsimConfigVersion.cmake
        DESTINATION ${TCPMSIM_CMAKE_DIR})
