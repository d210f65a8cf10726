# What both CLI test scripts share: the bundled log, a clean work folder, and the checks.
cmake_policy(SET CMP0007 NEW)  # lists keep empty elements: CSV rows split on commas keep their columns
set(LOG ${SOURCE_DIR}/data/office/L-hokuyo-2hz.clf)
set(GT ${SOURCE_DIR}/data/office/L-hokuyo-2hz.gt.tum)
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR})

# Runs the tool and fails unless it exits with `code`; LAST_OUT and LAST_ERR keep its output.
function(expect_run code)
  execute_process(COMMAND ${TOOL} ${ARGN} RESULT_VARIABLE result OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT result EQUAL code)
    message(FATAL_ERROR "contour_reg ${ARGN}: exit ${result}, expected ${code}\n${out}\n${err}")
  endif()
  set(LAST_OUT "${out}" PARENT_SCOPE)
  set(LAST_ERR "${err}" PARENT_SCOPE)
endfunction()

function(expect_match text pattern)
  if(NOT text MATCHES "${pattern}")
    message(FATAL_ERROR "expected /${pattern}/ in:\n${text}")
  endif()
endfunction()

# Sets `variable` to the first group of `pattern` in `text`; fails when `text` has no match.
function(number_in text pattern variable)
  if(NOT text MATCHES "${pattern}")
    message(FATAL_ERROR "expected /${pattern}/ in:\n${text}")
  endif()
  set(${variable} ${CMAKE_MATCH_1} PARENT_SCOPE)
endfunction()

# The end-point error (% of the path) that `evaluate` printed.
set(END_POINT_PERCENT "end-point error: [0-9.]+ m over [0-9.]+ m of ground-truth path = ([0-9.]+) %")
