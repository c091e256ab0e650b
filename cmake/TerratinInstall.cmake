# Install rules: the libraries, the public headers (and the generated version header), the
# terratin command line, and a CMake package (terratinConfig.cmake) exporting terratin::core
# and, when built, terratin::io. A consumer does find_package(terratin REQUIRED); see docs/cpp.md.
include(CMakePackageConfigHelpers)

set(TERRATIN_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/terratin CACHE STRING
  "Where terratinConfig.cmake is installed, relative to the prefix")

set(_terratin_libraries terratin_core)
if(TERRATIN_BUILD_IO)
  list(APPEND _terratin_libraries terratin_io)
endif()
install(TARGETS ${_terratin_libraries} EXPORT terratinTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
# The public headers are lib/include/terratin as a whole: none of them includes a lib/src one.
install(DIRECTORY ${PROJECT_SOURCE_DIR}/lib/include/terratin
  ${PROJECT_BINARY_DIR}/lib/include/terratin
  DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
# The command line only; the bench and dev tools stay in the build tree.
if(TARGET terratin)
  install(TARGETS terratin RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endif()

install(EXPORT terratinTargets NAMESPACE terratin:: DESTINATION ${TERRATIN_INSTALL_CMAKEDIR})
# TERRATIN_HAS_IO and the GeographicLib module folder are substituted into the config.
if(TERRATIN_BUILD_IO)
  set(TERRATIN_HAS_IO ON)
else()
  set(TERRATIN_HAS_IO OFF)
endif()
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/terratinConfig.cmake.in
  ${PROJECT_BINARY_DIR}/terratinConfig.cmake
  INSTALL_DESTINATION ${TERRATIN_INSTALL_CMAKEDIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/terratinConfigVersion.cmake
  COMPATIBILITY SameMajorVersion)
install(FILES ${PROJECT_BINARY_DIR}/terratinConfig.cmake
  ${PROJECT_BINARY_DIR}/terratinConfigVersion.cmake
  ${PROJECT_SOURCE_DIR}/cmake/TerratinGeographicLib.cmake
  DESTINATION ${TERRATIN_INSTALL_CMAKEDIR})
