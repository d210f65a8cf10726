# Installs the build tree into a scratch prefix, checks that no internal header was
# installed, then configures, builds and runs the consumer project against it.
file(REMOVE_RECURSE ${WORK_DIR})
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE result OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "failed: ${ARGN}\n${out}\n${err}")
  endif()
  message(STATUS "${out}")
endfunction()
run(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${WORK_DIR}/prefix)
# Only public headers are installed: none of the modules' internal ones (src/*.h), and every
# header an installed header includes is installed too.
file(GLOB_RECURSE installed RELATIVE ${WORK_DIR}/prefix/include ${WORK_DIR}/prefix/include/contour_reg/*)
file(GLOB internal RELATIVE ${SOURCE_DIR}/modules ${SOURCE_DIR}/modules/*/src/*.h)
list(LENGTH installed count)
message(STATUS "installed headers: ${count}")
foreach(header ${internal})
  get_filename_component(name ${header} NAME)
  foreach(path ${installed})
    get_filename_component(installed_name ${path} NAME)
    if(name STREQUAL installed_name)
      message(FATAL_ERROR "internal header ${header} installed as ${path}")
    endif()
  endforeach()
endforeach()
foreach(path ${installed})
  file(STRINGS ${WORK_DIR}/prefix/include/${path} includes REGEX "^#include \"contour_reg/")
  foreach(line ${includes})
    string(REGEX REPLACE "^#include \"([^\"]+)\".*" "\\1" included "${line}")
    if(NOT EXISTS ${WORK_DIR}/prefix/include/${included})
      message(FATAL_ERROR "${path} includes ${included}, which is not installed")
    endif()
  endforeach()
endforeach()

# A project(x CXX) and a project(x C CXX) consumer.
foreach(languages CXX C,CXX)
  string(REPLACE "," "-" name "${languages}")
  run(${CMAKE_COMMAND} -S ${SOURCE_DIR}/tests/consumer -B ${WORK_DIR}/build-${name}
      -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix "-DCONSUMER_LANGUAGES=${languages}")
  run(${CMAKE_COMMAND} --build ${WORK_DIR}/build-${name})
  run(${WORK_DIR}/build-${name}/consumer)
endforeach()

# The installed Python package imports from its install folder and registers a scan pair.
if(PYTHON)
  run(${CMAKE_COMMAND} -E env PYTHONPATH=${WORK_DIR}/prefix/${PYTHON_DIR} ${PYTHON} ${SOURCE_DIR}/tests/consumer/consumer.py
      ${WORK_DIR}/prefix/${PYTHON_DIR})
endif()
