# The contour_reg tool on bad command lines and references that cover nothing: every case
# exits with the documented code, names the option or the path, and writes nothing.
include(${CMAKE_CURRENT_LIST_DIR}/cli_test_support.cmake)

# Nothing may appear in the work folder but what a case writes on purpose.
function(expect_nothing_written)
  file(GLOB written ${WORK_DIR}/out/*)
  if(written)
    message(FATAL_ERROR "a refused command wrote ${written}")
  endif()
endfunction()
file(MAKE_DIRECTORY ${WORK_DIR}/out)
set(OUT ${WORK_DIR}/out)

# --version and a mistyped command.
file(STRINGS ${SOURCE_DIR}/CMakeLists.txt project_line REGEX "^project\\(contour_reg VERSION")
string(REGEX MATCH "[0-9]+\\.[0-9]+\\.[0-9]+" version "${project_line}")
expect_run(0 --version)
expect_match("${LAST_OUT}" "contour_reg ${version}")
expect_run(2 odometri ${LOG})
expect_match("${LAST_ERR}" "unknown command 'odometri'; did you mean 'odometry'")
expect_run(2 odometry ${LOG} --method nonsense --output ${OUT}/t.tum)
expect_match("${LAST_ERR}" "--method")

# Every invalid value exits 2 before any work, naming the option.
foreach(case "--arm;0" "--threshold;-1" "--contour-step;0" "--candidates;0" "--local-fallback;40" "--max-range;-5"
             "--icp-max-distance;-1" "--iterations;0" "--ndt-resolution;0" "--probe-distance;-1" "--threshold;abc"
             "--local-map;-1" "--frame;map" "--laser-pose;0.1;0" "--laser-pose;0;0;nan" "--laser-pose;a;b;c"
             "--wheel-noise;0.1;0.1;0.1" "--wheel-noise;0.1;0.1;-0.1;0.1" "--wheel-noise;0.1;inf;0.1;0.1"
             "--beam-step;0" "--beam-step;1.5" "--contour-step;0.000001" "--scan-period;100"
             "--laser-pose;1000;0;0" "--laser-pose;0;0;1e300")
  list(GET case 0 option)
  expect_run(2 odometry ${LOG} -m ndt2d --output ${OUT}/t.tum ${case})
  expect_match("${LAST_ERR}" "${option}")
  expect_nothing_written()
endforeach()
# relations takes one reference: a relations file, the log's poses or a ground truth.
foreach(case "--gt-gap;2" "--gt;${GT};--log-poses;1" "--gt;${GT};--gt-gap;0" "--gt;${OUT}/missing.gt.tum")
  list(GET case 0 option)
  expect_run(2 relations ${LOG} --methods contour --pairs-csv ${OUT}/pairs.csv ${case})
  expect_match("${LAST_ERR}" "--gt")
  expect_nothing_written()
endforeach()
# The reference's error for the NEES line: two numbers, neither negative.
foreach(case "--reference-sigma;0.05" "--reference-sigma;0.05;-1")
  expect_run(2 relations ${LOG} --log-poses 1 --methods contour ${case})
  expect_match("${LAST_ERR}" "--reference-sigma")
endforeach()
expect_run(2 debug ${LOG} --threshold -1 --out ${OUT}/pictures)
expect_match("${LAST_ERR}" "--threshold")
expect_run(2 experiment --odometry-noise -1 --out ${OUT}/experiment)
expect_match("${LAST_ERR}" "--odometry-noise")
expect_run(2 simulate --odometry-rate -5 -o ${OUT}/run.clf)
expect_match("${LAST_ERR}" "--odometry-rate")
# A run longer than any simulation: refused with its size, nothing written.
expect_run(2 simulate --speed 1e-300 -o ${OUT}/run.clf)
expect_match("${LAST_ERR}" "error: a run of .* scans \\(a path of .* m at 1e-300 m/s")
expect_run(2 experiment --guess odom --wheel-noise 0.1 -1 0.1 0.1 --out ${OUT}/experiment)
expect_match("${LAST_ERR}" "--wheel-noise")
expect_run(2 compare ${LOG} --guess odom --wheel-noise 0.1 0.1 --out ${OUT}/compare)
expect_match("${LAST_ERR}" "--wheel-noise")
expect_run(2 experiment --rates 0 --out ${OUT}/experiment)
expect_match("${LAST_ERR}" "--rates: 0 is out of range: must be > 0")
expect_nothing_written()
# The experiment checks the size of each run before it simulates one: its folder stays empty.
expect_run(2 experiment --odometry-rate 1e12 --out ${WORK_DIR}/long-experiment)
expect_match("${LAST_ERR}" "error: a run of .* wheel odometry samples")
file(GLOB written ${WORK_DIR}/long-experiment/*)
if(written)
  message(FATAL_ERROR "a refused experiment wrote ${written}")
endif()

# Outputs are checked before any work: a file where a folder goes, a folder that does not exist.
file(WRITE ${WORK_DIR}/a_file "")
expect_run(2 debug ${LOG} --scan 30 --out ${WORK_DIR}/a_file)
expect_match("${LAST_ERR}" "a_file: exists and is not a folder")
expect_run(2 odometry ${LOG} --output ${OUT}/t.tum --debug-dir ${WORK_DIR}/a_file)
expect_match("${LAST_ERR}" "a_file: exists and is not a folder")
expect_run(2 odometry ${LOG} -m icp --output ${WORK_DIR}/missing/dir/t.tum)
expect_match("${LAST_ERR}" "--output: .*missing/dir/t.tum: folder .* does not exist")
expect_run(2 debug ${LOG} --scan 0 --out ${OUT}/pictures)
expect_match("${LAST_ERR}" "scan 0 has no scan before it")
expect_run(2 register ${LOG} --scan 0)
expect_match("${LAST_ERR}" "scan 0 has no scan before it")
expect_run(2 register ${LOG} --scan 500)
expect_match("${LAST_ERR}" "--scan 500, --to 499: .*L-hokuyo-2hz.clf has scans 0..98")
expect_run(2 register ${LOG} --guess 1 nan 0)
expect_match("${LAST_ERR}" "--guess: X Y YAW must be finite numbers")
expect_run(2 debug ${LOG} --scan 30 --reference 1 inf 0 --out ${OUT}/pictures)
expect_match("${LAST_ERR}" "--reference: X Y YAW must be finite numbers")
expect_run(2 debug ${LOG} --scan 30 --reference 1 0 0 --log-poses --out ${OUT}/pictures)
expect_match("${LAST_ERR}" "--reference excludes --log-poses")
expect_run(1 debug ${LOG} --scan 30 --log-poses --no-wheel-odometry --out ${WORK_DIR}/no-poses)
expect_match("${LAST_ERR}" "L-hokuyo-2hz.clf's poses: no pose at scan 29")
expect_run(2 register ${LOG} --scan 30 --reference 1 0 0 --gt ${GT})
expect_match("${LAST_ERR}" "--reference excludes --gt")
expect_run(1 register ${LOG} --scan 30 --log-poses --no-wheel-odometry)
expect_match("${LAST_ERR}" "L-hokuyo-2hz.clf's poses: no pose at scan 29")
expect_run(2 register ${LOG} --scan 30 --gt ${GT} --reference-sigma -1 0)
expect_match("${LAST_ERR}" "--reference-sigma: -1 is out of range")
expect_run(2 register ${LOG} --methods icp bogus)
expect_match("${LAST_ERR}" "--methods")
expect_nothing_written()

# A missing input is found before an output folder is made.
expect_run(2 compare ${WORK_DIR}/missing.clf --out ${OUT}/compare)
expect_match("${LAST_ERR}" "missing.clf")
expect_run(2 experiment --map ${WORK_DIR}/missing.yaml --out ${OUT}/experiment)
expect_match("${LAST_ERR}" "missing.yaml")
expect_nothing_written()

# evaluate refuses to score a ground truth of another run, or relations it does not cover.
file(STRINGS ${GT} gt_lines REGEX "^[0-9]")
set(shifted "")
foreach(line IN LISTS gt_lines)
  string(REGEX REPLACE "^([0-9]+)" "9\\1" line "${line}")  # the same poses, stamps far later
  string(APPEND shifted "${line}\n")
endforeach()
file(WRITE ${WORK_DIR}/other.gt.tum "${shifted}")
expect_run(1 evaluate ${GT} --gt ${WORK_DIR}/other.gt.tum)
expect_match("${LAST_ERR}" "share 0 stamps")
file(WRITE ${WORK_DIR}/other.relations "1000001.0 1000002.0 0.5 0 0 0 0 0\n1000003.0 1000004.0 0.5 0 0 0 0 0\n")
expect_run(1 evaluate ${GT} --relations ${WORK_DIR}/other.relations)
expect_match("${LAST_ERR}" "covers none of the 2 relations")
expect_run(0 evaluate ${GT} --gt ${GT})
expect_match("${LAST_OUT}" "ground truth: 99 of 99 poses matched")
# relations likewise: relations or a ground truth of another run pair no scans of this log.
expect_run(1 relations ${LOG} --relations ${WORK_DIR}/other.relations --methods contour)
expect_match("${LAST_ERR}" "no scan pair: none of the 2 relations has a scan of .*L-hokuyo-2hz.clf at both stamps")
expect_run(1 relations ${LOG} --gt ${WORK_DIR}/other.gt.tum --methods contour)
expect_match("${LAST_ERR}" "no scan pair: .*other.gt.tum has no pose at the stamps of scans 1 apart")
# A ground truth gives one pose per stamp: a relations file given as one (8 numbers a line too,
# its first stamps repeated with other motions) is refused, as evaluate refuses it.
set(twice "")
foreach(line IN LISTS gt_lines)
  string(REGEX REPLACE "^([0-9.]+) [-0-9.e]+" "\\1 100" moved "${line}")  # the same stamp, another pose
  string(APPEND twice "${line}\n${moved}\n")
endforeach()
file(WRITE ${WORK_DIR}/twice.gt.tum "${twice}")
expect_run(1 relations ${LOG} --gt ${WORK_DIR}/twice.gt.tum --methods contour)
expect_match("${LAST_ERR}" "twice.gt.tum: 99 of its 198 stamps are no later than the one before: they do not tell its poses apart")

# closure needs three scans, and checks its options before any work.
file(STRINGS ${LOG} laser_lines REGEX "^(FLASER|ROBOTLASER1) ")
list(SUBLIST laser_lines 0 2 two_lines)
string(REPLACE ";" "\n" two_scans "${two_lines}")
file(WRITE ${WORK_DIR}/two.clf "${two_scans}\n")
expect_run(1 closure ${WORK_DIR}/two.clf)
expect_match("${LAST_ERR}" "no triangle: .*two.clf has 2 scans, need 3")
expect_run(2 closure ${LOG} --threshold -1 --triangles-csv ${OUT}/t.csv)
expect_match("${LAST_ERR}" "--threshold")
expect_run(2 convert ${LOG} ${WORK_DIR}/missing/t.mcap)
expect_match("${LAST_ERR}" "output: .*missing/t.mcap: folder")
expect_run(2 closure ${LOG} --triangles-csv ${WORK_DIR}/missing/t.csv)
expect_match("${LAST_ERR}" "--triangles-csv: .*missing/t.csv: folder")
expect_nothing_written()

# simulate writes its ground truth where compare finds it.
expect_run(2 simulate --path line --rate 2 --output ${WORK_DIR}/nowhere/s.clf)
expect_match("${LAST_ERR}" "--output: .*nowhere/s.clf: folder")
file(MAKE_DIRECTORY ${WORK_DIR}/sim)
expect_run(0 simulate --path line --rate 2 -o ${WORK_DIR}/sim/s.clf)
expect_run(0 compare ${WORK_DIR}/sim/s.clf --methods contour --out ${WORK_DIR}/sim/compare)
expect_match("${LAST_ERR}" "s.clf: [0-9]+ scans, ground truth")
expect_match("${LAST_OUT}" "\\| s \\| contour \\| [0-9]+ / [0-9]+ \\| - \\| - \\| - \\| [0-9.]+ \\|")
# With --log-poses the log's own poses (here exact wheel odometry) are the ground truth, and the
# methods run on the scans alone (neither the deskewing of timed scans nor the fusion reads
# the poses): the trajectory and its score are those of the scans alone against the TUM ground
# truth, and no wheel-odometry row scores the reference against itself.
expect_run(0 simulate --path S --rate 2 --odometry-noise 0 -o ${WORK_DIR}/sim/exact.clf)
expect_run(0 compare ${WORK_DIR}/sim/exact.clf --methods contour --scan-period 0.1 --log-poses --out ${WORK_DIR}/sim/by-log)
number_in("${LAST_OUT}" "\\| exact \\| contour \\| [0-9]+ / [0-9]+ \\| - \\| - \\| - \\| ([0-9.]+) \\|" by_log)
if(LAST_OUT MATCHES "wheel-odometry")
  message(FATAL_ERROR "compare --log-poses scored the log's poses against themselves:\n${LAST_OUT}")
endif()
expect_run(0 compare ${WORK_DIR}/sim/exact.clf --methods contour --scan-period 0.1 --no-wheel-odometry
           --out ${WORK_DIR}/sim/by-gt)
number_in("${LAST_OUT}" "\\| exact \\| contour \\| [0-9]+ / [0-9]+ \\| - \\| - \\| - \\| ([0-9.]+) \\|" by_gt)
file(READ ${WORK_DIR}/sim/by-log/exact.contour.tum by_log_trajectory)
file(READ ${WORK_DIR}/sim/by-gt/exact.contour.tum by_gt_trajectory)
if(NOT by_log_trajectory STREQUAL by_gt_trajectory OR NOT by_log STREQUAL by_gt)
  message(FATAL_ERROR "compare --log-poses: end point ${by_log} % against the ground truth's ${by_gt} %, "
                      "or the methods read the log's poses")
endif()
expect_run(2 compare ${WORK_DIR}/sim/exact.clf --log-poses --gt ${WORK_DIR}/sim/exact.gt.tum --out ${OUT}/compare)
expect_match("${LAST_ERR}" "--gt excludes --log-poses")
expect_run(2 compare ${WORK_DIR}/sim/exact.clf --log-poses --guess odom --out ${OUT}/compare)
expect_match("${LAST_ERR}" "--guess odom: would start each registration from the log's poses")
expect_run(2 compare ${WORK_DIR}/sim/exact.clf --log-poses --no-wheel-odometry --out ${OUT}/compare)
expect_match("${LAST_ERR}" "exact.clf: --log-poses, but the log has no poses of its own \\(read with --no-wheel-odometry\\)")
# A log that kept no stamps (as some Radish logs, stamped 0 or to six digits): its scans and the
# poses they carry are paired by scan order, and score as the stamped log does. Its stamps
# cannot pair a trajectory with a ground truth: evaluate gives no metric rather than a false one.
expect_run(0 simulate --path S --rate 2 --odometry-noise 0 --odometry-rate 0 -o ${WORK_DIR}/sim/stamped.clf)
file(READ ${WORK_DIR}/sim/stamped.clf stamped)
string(REGEX REPLACE " [0-9.]+ sim [0-9.]+\n" " 0 sim 0\n" unstamped "${stamped}")
file(WRITE ${WORK_DIR}/sim/unstamped.clf "${unstamped}")
foreach(log stamped unstamped)
  expect_run(0 compare ${WORK_DIR}/sim/${log}.clf --methods contour --log-poses --out ${WORK_DIR}/sim/${log})
  number_in("${LAST_OUT}" "\\| ${log} \\| contour \\| [0-9]+ / [0-9]+ \\| - \\| - \\| - \\| ([0-9.]+) \\|" end_point_${log})
endforeach()
expect_match("${LAST_ERR}" "unstamped.clf: [0-9]+ of [0-9]+ scans are stamped no later than the one before: the trajectories are paired with the log's poses by scan order")
if(NOT end_point_stamped STREQUAL end_point_unstamped)
  message(FATAL_ERROR "compare --log-poses: ${end_point_unstamped} % by scan order, ${end_point_stamped} % by stamp")
endif()
expect_run(1 evaluate ${WORK_DIR}/sim/unstamped/unstamped.contour.tum --gt ${WORK_DIR}/sim/unstamped/unstamped.contour.tum)
expect_match("${LAST_ERR}" "unstamped.contour.tum: [0-9]+ of its [0-9]+ stamps are no later than the one before: they do not tell its poses apart, and no metric is given")

# features reads every input kind: a ROS bag when the shared datasets are there.
set(BAG ${SOURCE_DIR}/../shared/datasets/intel/intel.orig.bag)
if(EXISTS ${BAG})
  expect_run(0 features ${BAG} --scan 5)
  expect_match("${LAST_ERR}" "scan 5: 180 beams")
endif()
expect_run(0 features ${LOG} --scan 10 --threshold 0.1 --arm 6)
expect_run(2 features ${LOG} --scan 10 --arm 0)
expect_match("${LAST_ERR}" "--arm")
message(STATUS "cli errors: all checks passed")
