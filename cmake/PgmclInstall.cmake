# `cmake --install` exports a CMake package: find_package(pgmcl) gives pgmcl::<component>.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

get_property(components GLOBAL PROPERTY PGMCL_COMPONENTS)
set(export_targets)
foreach(c IN LISTS components)
  list(APPEND export_targets pgmcl_${c})
endforeach()
install(TARGETS ${export_targets} EXPORT pgmclTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(EXPORT pgmclTargets NAMESPACE pgmcl:: DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/pgmcl)
configure_package_config_file(${CMAKE_CURRENT_SOURCE_DIR}/cmake/pgmclConfig.cmake.in
  ${CMAKE_CURRENT_BINARY_DIR}/pgmclConfig.cmake
  INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/pgmcl)
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/pgmclConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/pgmclConfig.cmake
  ${CMAKE_CURRENT_BINARY_DIR}/pgmclConfigVersion.cmake
  DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/pgmcl)
