# GeographicLib::GeographicLib, an imported target over the variables of GeographicLib's Find
# module (which defines no target), so that terratin::io's exported link interface names a
# target that terratinConfig.cmake defines again, not a library path of the build machine.
# Included after find_package(GeographicLib) by the top-level CMakeLists.txt and by the
# installed terratinConfig.cmake.
if(NOT TARGET GeographicLib::GeographicLib)
  add_library(GeographicLib::GeographicLib UNKNOWN IMPORTED)
  set_target_properties(GeographicLib::GeographicLib PROPERTIES
    IMPORTED_LOCATION "${GeographicLib_LIBRARIES}"
    INTERFACE_INCLUDE_DIRECTORIES "${GeographicLib_INCLUDE_DIRS}")
endif()
