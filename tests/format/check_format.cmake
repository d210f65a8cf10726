# Fails when a C++ source differs from what clang-format makes of it with .clang-format.
file(GLOB_RECURSE sources
  ${SOURCE_DIR}/apps/*.cc ${SOURCE_DIR}/apps/*.h
  ${SOURCE_DIR}/modules/*.cc ${SOURCE_DIR}/modules/*.h ${SOURCE_DIR}/modules/*.hpp
  ${SOURCE_DIR}/tests/*.cc ${SOURCE_DIR}/tests/*.h
  ${SOURCE_DIR}/benchmarks/*.cc ${SOURCE_DIR}/benchmarks/*.h
  ${SOURCE_DIR}/python/*.cc ${SOURCE_DIR}/python/*.h)
list(LENGTH sources count)
execute_process(COMMAND ${CLANG_FORMAT} --style=file --dry-run --Werror ${sources}
  RESULT_VARIABLE result ERROR_VARIABLE errors)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "${errors}\nnot formatted: run clang-format -i on the files above")
endif()
message(STATUS "${count} sources formatted")
