# contour_reg_add_module(NAME SOURCES ... [PUBLIC ...] [PRIVATE ...])
# Adds the library contour_reg_NAME, exported as contour_reg::NAME, whose public headers
# live in include/ beside this module's CMakeLists.txt.
function(contour_reg_add_module name)
  cmake_parse_arguments(ARG "" "" "SOURCES;PUBLIC;PRIVATE" ${ARGN})
  set(target contour_reg_${name})
  add_library(${target} ${ARG_SOURCES})
  add_library(contour_reg::${name} ALIAS ${target})
  set_target_properties(${target} PROPERTIES EXPORT_NAME ${name} OUTPUT_NAME ${target})
  target_include_directories(${target} PUBLIC
    $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>
    $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  target_link_libraries(${target} PUBLIC ${ARG_PUBLIC} PRIVATE ${ARG_PRIVATE})
  contour_reg_set_warnings(${target})
  install(DIRECTORY include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
  install(TARGETS ${target} EXPORT contour_regTargets)
endfunction()
