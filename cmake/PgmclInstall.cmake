# `cmake --install` exports a CMake package with one export set per component, so
# find_package(pgmcl COMPONENTS mcl) loads the engine and what it needs, and no more: a
# node that gets its grid from a message needs neither yaml-cpp, zlib nor stb.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(pgmcl_cmake_dir ${CMAKE_INSTALL_LIBDIR}/cmake/pgmcl)
get_property(components GLOBAL PROPERTY PGMCL_COMPONENTS)
foreach(c IN LISTS components)
  install(TARGETS pgmcl_${c} EXPORT pgmcl_${c}Targets
    ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
    LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
    INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
  install(EXPORT pgmcl_${c}Targets NAMESPACE pgmcl:: DESTINATION ${pgmcl_cmake_dir})
endforeach()
configure_package_config_file(${CMAKE_CURRENT_SOURCE_DIR}/cmake/pgmclConfig.cmake.in
  ${CMAKE_CURRENT_BINARY_DIR}/pgmclConfig.cmake INSTALL_DESTINATION ${pgmcl_cmake_dir})
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/pgmclConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/pgmclConfig.cmake
  ${CMAKE_CURRENT_BINARY_DIR}/pgmclConfigVersion.cmake DESTINATION ${pgmcl_cmake_dir})
