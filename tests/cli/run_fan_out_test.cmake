# A comparison spread over jobs: the plan run by GNU parallel in two jobs and merged gives the
# single run's table, except the times; a merge before the jobs have run, and a job the plan
# does not have, are refused naming what is missing.
include(${CMAKE_CURRENT_LIST_DIR}/cli_test_support.cmake)

# The lines of `file`, each with what matches `tail` cut off (the time columns), into `var`.
function(read_without_times file tail var)
  file(STRINGS ${file} lines)
  set(text "")
  foreach(line ${lines})
    string(REGEX REPLACE "${tail}" "" line "${line}")
    string(APPEND text "${line}\n")
  endforeach()
  set(${var} "${text}" PARENT_SCOPE)
endfunction()

set(STUDY compare ${LOG} --methods contour ndt2d)

expect_run(0 ${STUDY} --out ${WORK_DIR}/single -j 1)

expect_run(2 ${STUDY} --out ${WORK_DIR}/fan --merge)
expect_match("${LAST_ERR}" "no result of job L-hokuyo-2hz contour")
expect_run(2 ${STUDY} --out ${WORK_DIR}/fan --job 2)
expect_match("${LAST_ERR}" "--job.*the plan has 2 jobs")
expect_run(2 ${STUDY} --out ${WORK_DIR}/fan --plan --merge)

expect_run(0 ${STUDY} --out ${WORK_DIR}/fan --plan)
file(STRINGS ${WORK_DIR}/fan/plan.txt plan)
list(LENGTH plan jobs)
if(NOT jobs EQUAL 2)
  message(FATAL_ERROR "expected 2 jobs in the plan, found ${jobs}:\n${plan}")
endif()
execute_process(COMMAND ${PARALLEL} --will-cite -j 2 INPUT_FILE ${WORK_DIR}/fan/plan.txt
                RESULT_VARIABLE result ERROR_VARIABLE err)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "parallel ran the plan with exit ${result}:\n${err}")
endif()
expect_match("${err}" "job 2/2 done: L-hokuyo-2hz ndt2d")  # one line per job, stderr not a terminal
expect_run(0 ${STUDY} --out ${WORK_DIR}/fan --merge)

# A record that is not what a job writes is refused naming the file and the value: a count
# that is negative or not whole, a number that does not parse.
set(record ${WORK_DIR}/fan/jobs/L-hokuyo-2hz.contour.txt)
file(READ ${record} good_record)
foreach(bad "failures -5" "registrations 1e300" "failures 2.5" "median_ms fast")
  string(REGEX MATCH "^[a-z_]+" name "${bad}")
  string(REGEX REPLACE "${name} [^\n]*" "${bad}" bad_record "${good_record}")
  file(WRITE ${record} "${bad_record}")
  expect_run(2 ${STUDY} --out ${WORK_DIR}/fan --merge)
  expect_match("${LAST_ERR}" "L-hokuyo-2hz.contour.txt.*${name}")
endforeach()
file(WRITE ${record} "${good_record}")
expect_run(0 ${STUDY} --out ${WORK_DIR}/fan --merge)

# results.csv without its last two columns (median and p95 ms), and table.md without its
# last two cells: the same.
foreach(run single fan)
  read_without_times(${WORK_DIR}/${run}/results.csv ",[^,]*,[^,]*$" ${run}_csv)
  read_without_times(${WORK_DIR}/${run}/table.md "\\|[^|]*\\|[^|]*\\|$" ${run}_table)
endforeach()
if(NOT single_csv STREQUAL fan_csv OR NOT single_table STREQUAL fan_table)
  message(FATAL_ERROR "the merged table differs from the single run's:\n${single_table}\n${fan_table}")
endif()
string(REGEX MATCHALL "\n" rows "${fan_csv}")
list(LENGTH rows count)
if(NOT count EQUAL 4)  # header, contour, ndt2d, wheel odometry
  message(FATAL_ERROR "expected 4 lines in results.csv:\n${fan_csv}")
endif()
expect_match("${fan_csv}" "L-hokuyo-2hz,contour,98,0,")

# The paper's experiment the same way: one job per arrival.
set(EXPERIMENT experiment --paths S --rates 5 --arrivals 2 --methods contour)
expect_run(0 ${EXPERIMENT} --out ${WORK_DIR}/exp-single -j 1)
expect_run(0 ${EXPERIMENT} --out ${WORK_DIR}/exp-fan --plan)
execute_process(COMMAND ${PARALLEL} --will-cite -j 2 INPUT_FILE ${WORK_DIR}/exp-fan/plan.txt
                RESULT_VARIABLE result ERROR_VARIABLE err)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "parallel ran the experiment's plan with exit ${result}:\n${err}")
endif()
expect_match("${err}" "job 2/2 done: S-5hz-a1")
expect_run(0 ${EXPERIMENT} --out ${WORK_DIR}/exp-fan --merge)
foreach(run exp-single exp-fan)
  read_without_times(${WORK_DIR}/${run}/arrivals.csv ",[^,]*$" ${run}_csv)  # all but median_ms
endforeach()
if(NOT exp-single_csv STREQUAL exp-fan_csv)
  message(FATAL_ERROR "the merged arrivals differ from the single run's:\n${exp-single_csv}\n${exp-fan_csv}")
endif()
expect_match("${exp-fan_csv}" "S,5,1,contour,")
if(NOT EXISTS ${WORK_DIR}/exp-fan/trajectories/S-5hz.png)
  message(FATAL_ERROR "the merge drew no trajectory picture")
endif()
