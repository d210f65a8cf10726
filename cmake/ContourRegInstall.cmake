# Installs the exported targets and a package config, so that a separate project can do
#   find_package(contour_reg REQUIRED)
#   target_link_libraries(app PRIVATE contour_reg::contour_reg)
include(CMakePackageConfigHelpers)

# The umbrella target: everything a PCL pipeline needs.
add_library(contour_reg INTERFACE)
add_library(contour_reg::contour_reg ALIAS contour_reg)
target_link_libraries(contour_reg INTERFACE contour_reg::core contour_reg::pcl contour_reg::io contour_reg::odometry contour_reg::evaluation)
install(TARGETS contour_reg EXPORT contour_regTargets)

set(CONTOUR_REG_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/contour_reg)
install(EXPORT contour_regTargets NAMESPACE contour_reg:: DESTINATION ${CONTOUR_REG_CMAKE_DIR})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/contour_regConfig.cmake.in
  ${PROJECT_BINARY_DIR}/contour_regConfig.cmake INSTALL_DESTINATION ${CONTOUR_REG_CMAKE_DIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/contour_regConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/contour_regConfig.cmake ${PROJECT_BINARY_DIR}/contour_regConfigVersion.cmake
  DESTINATION ${CONTOUR_REG_CMAKE_DIR})
