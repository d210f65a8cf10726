# Runs the contour_reg tool's subcommands on the bundled log and checks exit codes and outputs.
include(${CMAKE_CURRENT_LIST_DIR}/cli_test_support.cmake)

# Every subcommand has --help.
foreach(command features simulate convert odometry evaluate compare register relations closure debug)
  expect_run(0 ${command} --help)
endforeach()

# convert writes the bundled log as a ROS 2 bag (MCAP, sqlite3): the odometry of each is the
# log's, up to the single precision of a LaserScan's angles (the CARMEN log's are double).
expect_run(0 odometry ${LOG} --output ${WORK_DIR}/carmen.tum)
foreach(storage mcap db3)
  expect_run(0 convert ${LOG} ${WORK_DIR}/converted.${storage})
  expect_match("${LAST_ERR}" "written: .*converted.${storage}, 99 scans")
  expect_run(0 odometry ${WORK_DIR}/converted.${storage} --output ${WORK_DIR}/converted-${storage}.tum)
  expect_run(0 evaluate ${WORK_DIR}/converted-${storage}.tum --gt ${WORK_DIR}/carmen.tum)
  expect_match("${LAST_OUT}" "end-point error: 0\\.000 m over 24\\.40 m")
  expect_match("${LAST_OUT}" "ATE after SE\\(2\\) alignment: 0\\.000 m RMSE")
endforeach()

# odometry writes one TUM line per scan.
expect_run(0 odometry ${LOG} --method contour --output ${WORK_DIR}/contour.tum --debug-dir ${WORK_DIR}/debug --debug-every 10
           --covariance ${WORK_DIR}/steps.csv)
# ... and one covariance row per registration, each converged with a positive variance.
file(STRINGS ${WORK_DIR}/steps.csv rows REGEX ",1,converged,")
list(LENGTH rows count)
if(NOT count EQUAL 98)
  message(FATAL_ERROR "odometry --covariance wrote ${count} converged rows, expected 98")
endif()
list(GET rows 0 first)
string(REPLACE "," ";" fields "${first}")
list(GET fields 7 variance_x)
if(NOT variance_x MATCHES "^[1-9]\\.[0-9]+e-0[0-9]$")
  message(FATAL_ERROR "odometry --covariance: variance of x '${variance_x}' is not a positive number")
endif()
file(STRINGS ${WORK_DIR}/contour.tum lines REGEX "^[0-9]")
list(LENGTH lines count)
if(NOT count EQUAL 99)
  message(FATAL_ERROR "odometry wrote ${count} poses, expected 99")
endif()
file(GLOB pictures ${WORK_DIR}/debug/pair_*.png)
if(NOT pictures)
  message(FATAL_ERROR "odometry --debug-dir wrote no pair image")
endif()
# Against a local map, the pictures show the map each scan was registered against.
expect_run(0 odometry ${LOG} --local-map 3 --output ${WORK_DIR}/mapped.tum --debug-dir ${WORK_DIR}/debug-map
           --debug-every 10)
file(GLOB pictures ${WORK_DIR}/debug-map/pair_*.png)
file(GLOB map_pictures ${WORK_DIR}/debug-map/pair_map*.png)
if(NOT map_pictures OR NOT pictures STREQUAL map_pictures)
  message(FATAL_ERROR "odometry --local-map --debug-dir wrote ${pictures}, not pair_map<keyframe>_<scan>.png")
endif()

# register prints each method's answer for one pair as YAML. The bundled log's scans 0 and 1 lie
# 0.25 m apart straight ahead (its ground truth): the contour method finds that within 1 cm and
# 0.5 deg, with a covariance; ICP converges too and gives none.
expect_run(0 register ${LOG} --scan 1 --methods contour icp)
string(REGEX MATCH "- method: contour\n  status: converged\n  motion: {x_m: 0\\.2[45][0-9]+, y_m: -?0\\.00[0-9]+, yaw_deg: -?0\\.[0-4][0-9]+}\n  covariance: \\[[^]]+\\]\n" contour "${LAST_OUT}")
if(NOT contour)
  message(FATAL_ERROR "register: no converged contour answer within 1 cm / 0.5 deg of (0.25 m, 0, 0) in:\n${LAST_OUT}")
endif()
expect_match("${LAST_OUT}" "- method: icp\n  status: converged\n  motion: {x_m: [-0-9.]+, y_m: [-0-9.]+, yaw_deg: [-0-9.]+}\n  milliseconds: ")
# Scan 90 lies in another room than scan 0: the contour method declines the pair, says why, and
# prints no motion for it, only the one it weighed and declined.
expect_run(0 register ${LOG} --scan 90 --to 0 --methods contour)
expect_match("${LAST_OUT}" "- method: contour\n  status: low_overlap\n  reason: \"[^\"]+\"\n  declined: {x_m: ")
if(LAST_OUT MATCHES "\n  (motion|covariance):")
  message(FATAL_ERROR "register printed a motion or covariance for a declined pair:\n${LAST_OUT}")
endif()
# With the pair's true motion (--gt, --log-poses or --reference), each converged answer says how far
# it lies from it and, with a covariance, its NEES; a motion weighed and not taken says the same.
# The ground truth gives 0.25 m straight ahead: the contour answer lies within 1 cm and 0.5 deg.
expect_run(0 register ${LOG} --scan 1 --gt ${GT})
expect_match("${LAST_OUT}" "# reference: {x_m: 0\\.2500, y_m: -?0\\.0000, yaw_deg: -?0\\.000}")
expect_match("${LAST_OUT}" "  error: {m: 0\\.00[0-9]+, deg: 0\\.[0-4][0-9]+}\n  nees: [0-9]+\\.[0-9]+\n")
# A reference 1 m ahead lies 0.75 m from that answer, far outside its covariance.
expect_run(0 register ${LOG} --scan 1 --reference 1 0 0)
expect_match("${LAST_OUT}" "  error: {m: 0\\.7[45][0-9]+, deg: 0\\.[0-4][0-9]+}\n  nees: [0-9][0-9][0-9]+\\.[0-9]+\n")
# Scan 90 lies 20.5 m and 90 deg from scan 0: the motion the contour method declined is far from it.
expect_run(0 register ${LOG} --scan 90 --to 0 --gt ${GT})
expect_match("${LAST_OUT}" "  declined_error: {m: [1-9][0-9]\\.[0-9]+, deg: ")

# evaluate prints the paper's metric against the ground truth.
expect_run(0 evaluate ${WORK_DIR}/contour.tum --gt ${GT})
expect_match("${LAST_OUT}" "end-point error: [0-9.]+ m over 24\\.[0-9]+ m")
expect_match("${LAST_OUT}" "ATE after SE\\(2\\) alignment")

# compare writes the table, the CSV, a trajectory per method and the trajectory picture.
expect_run(0 compare ${LOG} --methods contour icp --out ${WORK_DIR}/compare)
expect_match("${LAST_OUT}" "\\| L-hokuyo-2hz \\| contour \\|")
expect_match("${LAST_OUT}" "\\| L-hokuyo-2hz \\| icp \\|")
foreach(file table.md results.csv L-hokuyo-2hz.contour.tum L-hokuyo-2hz.icp.tum L-hokuyo-2hz.trajectories.png)
  if(NOT EXISTS ${WORK_DIR}/compare/${file})
    message(FATAL_ERROR "compare did not write ${file}")
  endif()
endforeach()

# compare runs each method as odometry does, the keyframe options included: a new keyframe
# after 1 m or 30 deg gives the same trajectory from both, and another from 0.3 m and 11.5 deg.
set(KEYFRAMES --keyframes --keyframe-distance 1 --keyframe-angle 30)
expect_run(0 odometry ${LOG} --method contour ${KEYFRAMES} --output ${WORK_DIR}/keyframes.tum)
expect_run(0 odometry ${LOG} --method contour --keyframes --output ${WORK_DIR}/keyframes-default.tum)
expect_run(0 compare ${LOG} --methods contour ${KEYFRAMES} --out ${WORK_DIR}/compare-keyframes)
file(READ ${WORK_DIR}/keyframes.tum by_odometry)
file(READ ${WORK_DIR}/keyframes-default.tum by_default)
file(READ ${WORK_DIR}/compare-keyframes/L-hokuyo-2hz.contour.tum by_compare)
if(NOT by_compare STREQUAL by_odometry)
  message(FATAL_ERROR "compare ${KEYFRAMES} wrote another trajectory than odometry with the same options")
endif()
if(by_odometry STREQUAL by_default)
  message(FATAL_ERROR "odometry: --keyframe-distance 1 --keyframe-angle 30 changed nothing")
endif()

# closure weighs how far registrations around triangles of scans fail to compose, by their
# covariances: a row per method ('-' where a method gives no covariance), a CSV row per triangle.
expect_run(0 closure ${LOG} --methods contour icp --triangles-csv ${WORK_DIR}/triangles.csv)
expect_match("${LAST_OUT}" "97 triangles of scans k, k \\+ 1, k \\+ 2")
expect_match("${LAST_OUT}" "\\| contour \\| ([0-9]+) of 97 \\| [0-9]+ \\| [0-9]+\\.[0-9][0-9] \\| [0-9.]+ % \\|")
string(REGEX MATCH "\\| contour \\| ([0-9]+) of" row "${LAST_OUT}")
set(closed_contour ${CMAKE_MATCH_1})
expect_match("${LAST_OUT}" "\\| icp \\| [0-9]+ of 97 \\| [0-9]+ \\| - \\| - \\| - \\| - \\|")
file(STRINGS ${WORK_DIR}/triangles.csv rows REGEX "^contour,")
list(LENGTH rows count)
if(NOT count EQUAL closed_contour)
  message(FATAL_ERROR "closure --triangles-csv wrote ${count} contour rows for ${closed_contour} closed triangles")
endif()

# With the log's poses, closure also weighs each k -> k + 1 registration against them. Scan 50's
# pose moved (x negated, robot and laser alike): the two registrations through it are far off the
# poses, and the triangle of scans 49, 50, 51 closes: the poses are off there, not the registrations.
if(LAST_OUT MATCHES "Against the log's own poses")
  message(FATAL_ERROR "closure without --log-poses printed the table against the poses")
endif()
file(STRINGS ${LOG} lines)
set(moved "")
set(scan -1)
foreach(line IN LISTS lines)
  if(line MATCHES "^ROBOTLASER1 ")
    math(EXPR scan "${scan} + 1")
    if(scan EQUAL 50)
      string(REPLACE " " ";" fields "${line}")
      list(GET fields 8 readings)
      math(EXPR at "9 + ${readings}")
      list(GET fields ${at} remissions)
      math(EXPR laser_x "10 + ${readings} + ${remissions}")
      math(EXPR robot_x "${laser_x} + 3")
      foreach(at ${laser_x} ${robot_x})
        list(GET fields ${at} value)
        list(REMOVE_AT fields ${at})
        list(INSERT fields ${at} "-${value}")
      endforeach()
      list(JOIN fields " " line)
    endif()
  endif()
  string(APPEND moved "${line}\n")
endforeach()
file(WRITE ${WORK_DIR}/moved_pose.clf "${moved}")
expect_run(0 closure ${LOG} --log-poses --limit 20)
expect_match("${LAST_OUT}" "\\| contour \\| 21 \\| 0 \\| 0 \\|")
expect_run(0 closure ${WORK_DIR}/moved_pose.clf --log-poses --methods contour icp)
expect_match("${LAST_OUT}" "\\| contour \\| 98 \\| 2 \\| 2 \\|")
expect_match("${LAST_OUT}" "\\| icp \\| [0-9]+ \\| [0-9]+ \\| - \\|")

# debug draws the scan and the pair.
expect_run(0 debug ${LOG} --scan 30 --out ${WORK_DIR}/pictures)
foreach(file scan_30.png pair_29_30.png)
  if(NOT EXISTS ${WORK_DIR}/pictures/${file})
    message(FATAL_ERROR "debug did not write ${file}")
  endif()
endforeach()
# With the pair's true motion, and from a guess, it draws the contour method's alignment beside it.
expect_run(0 debug ${LOG} --scan 30 --reference 0.2 0 1 --guess 0.1 0 0 --out ${WORK_DIR}/pictures-reference)
if(NOT EXISTS ${WORK_DIR}/pictures-reference/methods_29_30.png)
  message(FATAL_ERROR "debug --reference did not write methods_29_30.png")
endif()
expect_run(0 debug ${LOG} --scan 30 --gt ${GT} --out ${WORK_DIR}/pictures-gt)
if(NOT EXISTS ${WORK_DIR}/pictures-gt/methods_29_30.png)
  message(FATAL_ERROR "debug --gt did not write methods_29_30.png")
endif()

# experiment, reduced: one path, one rate, two arrivals; the table carries the paper's row.
expect_run(0 experiment --paths L --rates 5 --arrivals 2 --methods contour icp --out ${WORK_DIR}/experiment)
expect_match("${LAST_OUT}" "\\| 5 Hz \\| paper \\| 14\\.1 \\|")
expect_match("${LAST_OUT}" "\\| 5 Hz \\| contour \\| [0-9.]+ \\([0-9.]+\\) \\|")
foreach(file table.md arrivals.csv map.png trajectories/L-5hz.png)
  if(NOT EXISTS ${WORK_DIR}/experiment/${file})
    message(FATAL_ERROR "experiment did not write ${file}")
  endif()
endforeach()
# A laser mounted 0.3 m ahead of the robot's centre and turned 20 deg: the log says so
# (ROBOTLASER1), and odometry gives the robot's trajectory, which the ground truth is.
expect_run(0 simulate --path L --rate 2 --laser-pose 0.3 0 20 --out ${WORK_DIR}/mounted.log)
foreach(frame robot laser)
  expect_run(0 odometry ${WORK_DIR}/mounted.log --guess odom --frame ${frame} --output ${WORK_DIR}/mounted-${frame}.tum)
  file(READ ${WORK_DIR}/mounted-${frame}.tum written)
  expect_match("${written}" "^# frame: ${frame}")
  expect_run(0 evaluate ${WORK_DIR}/mounted-${frame}.tum --gt ${WORK_DIR}/mounted.gt.tum)
  number_in("${LAST_OUT}" "${END_POINT_PERCENT}" percent_${frame})
endforeach()
if(percent_robot GREATER 1 OR percent_laser LESS 5)
  message(FATAL_ERROR "mounted.log: end-point error ${percent_robot} % as the robot's, ${percent_laser} % as the laser's")
endif()
# register answers as the robot's motion too: 0.25 m straight ahead (the ground truth); as the
# laser's, the same step seen 20 deg turned, about 0.08 m to the right.
expect_run(0 register ${WORK_DIR}/mounted.log --scan 1)
expect_match("${LAST_OUT}" "  motion: {x_m: 0\\.2[45][0-9]+, y_m: -?0\\.00[0-9]+, yaw_deg: -?0\\.[0-4][0-9]+}")
expect_run(0 register ${WORK_DIR}/mounted.log --scan 1 --frame laser)
expect_match("${LAST_OUT}" "  motion: {x_m: 0\\.23[0-9]+, y_m: -0\\.0[78][0-9]+, yaw_deg: -?0\\.[0-4][0-9]+}")
# The ground truth holds the robot's poses: as the laser's, the reference is the laser's motion too.
expect_run(0 register ${WORK_DIR}/mounted.log --scan 1 --frame laser --gt ${WORK_DIR}/mounted.gt.tum)
expect_match("${LAST_OUT}" "  error: {m: 0\\.00[0-9]+, deg: 0\\.[0-4][0-9]+}")
# The wheel odometry left out, a guess from it is no guess at all: the tool says so.
expect_run(0 odometry ${LOG} --guess odom --no-wheel-odometry --output ${WORK_DIR}/no-wheels.tum)
expect_match("${LAST_ERR}" "warning: --guess odom, but .*L-hokuyo-2hz.clf has no wheel odometry")
expect_run(0 odometry ${LOG} --guess odom --output ${WORK_DIR}/wheels.tum)
if(LAST_ERR MATCHES "no wheel odometry")
  message(FATAL_ERROR "odometry --guess odom warned of no wheel odometry on a log that has it:\n${LAST_ERR}")
endif()

# A moving robot's run written as a ROS 1 bag with beam timing: odometry deskews it by default.
if(WITH_ROSBAG)
  expect_run(0 simulate --path S --rate 2 --motion continuous --out ${WORK_DIR}/moving.bag)
  foreach(mode deskew no-deskew)
    expect_run(0 odometry ${WORK_DIR}/moving.bag --${mode} --output ${WORK_DIR}/moving-${mode}.tum)
    expect_run(0 evaluate ${WORK_DIR}/moving-${mode}.tum --gt ${WORK_DIR}/moving.gt.tum)
    number_in("${LAST_OUT}" "${END_POINT_PERCENT}" percent_${mode})
  endforeach()
  if(NOT percent_deskew LESS 2 OR NOT percent_no-deskew GREATER 5)
    message(FATAL_ERROR "moving.bag: end-point error ${percent_deskew} % deskewed, ${percent_no-deskew} % raw")
  endif()
  # Without wheels a scan is first deskewed by the last motion; where a turn ends that bends a
  # scan taken straight, and the registration converges on a retry with the scan as taken.
  expect_run(0 simulate --path L --rate 5 --motion continuous --out ${WORK_DIR}/turning.bag)
  expect_run(0 odometry ${WORK_DIR}/turning.bag --no-wheel-odometry --output ${WORK_DIR}/turning.tum)
  expect_match("${LAST_OUT}" "registrations by contour, 0 failed")
  expect_match("${LAST_OUT}" "converged on a retry \\(from the prediction, or the scan as taken\\): [1-9]")
  # relations deskews the pairs it registers as the odometry does.
  foreach(mode deskew no-deskew)
    expect_run(0 relations ${WORK_DIR}/moving.bag --log-poses 1 --methods contour --${mode})
    number_in("${LAST_OUT}" "\\| contour \\| ([0-9.]+) %" recovered_${mode})
  endforeach()
  if(NOT recovered_deskew GREATER 95 OR NOT recovered_no-deskew LESS 90)
    message(FATAL_ERROR "moving.bag pairs: ${recovered_deskew} % recovered deskewed, ${recovered_no-deskew} % raw")
  endif()
  # The same run as a ROS 2 bag (sqlite3 or MCAP) reads as the ROS 1 bag does: the same trajectory.
  file(READ ${WORK_DIR}/moving-deskew.tum ros1_trajectory)
  foreach(storage db3 mcap)
    expect_run(0 simulate --path S --rate 2 --motion continuous --out ${WORK_DIR}/moving.${storage})
    expect_run(0 odometry ${WORK_DIR}/moving.${storage} --deskew --output ${WORK_DIR}/moving-${storage}.tum)
    file(READ ${WORK_DIR}/moving-${storage}.tum ros2_trajectory)
    if(NOT ros1_trajectory STREQUAL ros2_trajectory)
      message(FATAL_ERROR "moving.${storage} and moving.bag give different trajectories")
    endif()
  endforeach()
  # compare finds its ground truth beside it, as for the other logs.
  expect_run(0 compare ${WORK_DIR}/moving.db3 --methods contour --out ${WORK_DIR}/compare-ros2)
  expect_match("${LAST_OUT}" "\\| moving \\| contour \\| 0 / [0-9]+ \\| - \\| - \\| - \\| [0-9.]+ \\|")
endif()

# relations tells a reference the scans contradict from a registration failure: the robot drove
# 0.25 m straight ahead between the scans at 0 and 0.5 s and again up to 1 s; the second relation
# claims 1.5 m.
file(WRITE ${WORK_DIR}/straight.relations "0.0 0.5 0.25 0 0 0 0 0\n0.5 1.0 1.5 0 0 0 0 0\n")
expect_run(0 relations ${LOG} --relations ${WORK_DIR}/straight.relations --methods contour
           --pairs-csv ${WORK_DIR}/straight.csv)
expect_match("${LAST_OUT}" "contour: 1 gross error\\(s\\) [^\n]*, 1 with a reference the scans contradict and an estimate they do not[^\n]*; such a reference on 1 of all 1 converged but wrong")
if(LAST_OUT MATCHES "converged but wrong;")
  message(FATAL_ERROR "relations counts agreement with no independent method run:\n${LAST_OUT}")
endif()
# ... and point-to-line ICP, from the same zero guess, agrees with the contour estimate against
# that reference. contour+icp is no witness for contour (it starts from its estimate), nor ICP
# for point-to-line ICP (both descend from the same guess).
expect_run(0 relations ${LOG} --relations ${WORK_DIR}/straight.relations --methods contour contour+icp icp icp-pl)
expect_match("${LAST_OUT}" "contour: 1 converged but wrong; an independent method converged within 5 cm and 1 deg of 1 of them \\(icp 1, icp-pl 1\\)")
expect_match("${LAST_OUT}" "icp-pl: 1 converged but wrong; [^\n]* of 1 of them \\(contour 1, contour\\+icp 1\\)")
# The covariance line: the 1.25 m error of the second relation lies far outside the 99 %
# ellipsoid of the reported covariance and the 2 cm / 0.5 deg reference floor, the first pair
# inside; ICP and point-to-line ICP report no covariance, so no line, nor does contour+icp, whose
# ICP moves the contour estimate its covariance describes.
expect_match("${LAST_OUT}" "\ncontour: covariance: mean NEES [0-9.]+ over 2 converged pairs, 50.0 % above 11.34")
if(LAST_OUT MATCHES "\n(icp|icp-pl|contour\\+icp): covariance")
  message(FATAL_ERROR "relations reports a covariance for a method that gives none:\n${LAST_OUT}")
endif()
# A reference error of 0.5 m / 30 deg covers that 1.25 m error (NEES about 6).
expect_run(0 relations ${LOG} --relations ${WORK_DIR}/straight.relations --methods contour --reference-sigma 0.5 30)
expect_match("${LAST_OUT}" "contour: covariance: [^\n]*, 0.0 % above 11.34 [^\n]*0.5 m / 30 deg")
file(STRINGS ${WORK_DIR}/straight.csv rows REGEX "^contour,")
foreach(row IN LISTS rows)
  string(REPLACE "," ";" fields "${row}")
  list(GET fields 5 claimed)
  list(GET fields 24 reference_share)
  list(GET fields 25 estimate_share)
  # The estimate is hardly contradicted; the reference claiming 1.5 m is, the true one is not.
  if(NOT estimate_share LESS 0.02 OR (claimed STREQUAL "1.5000" AND NOT reference_share GREATER 0.1)
     OR (claimed STREQUAL "0.2500" AND NOT reference_share LESS 0.02))
    message(FATAL_ERROR "relations free space: reference ${reference_share}, estimate ${estimate_share} in ${row}")
  endif()
endforeach()
# A reference turned 4 deg too far is no gross error, yet converged but wrong, and the scans
# contradict it: it puts the far walls' returns in the other scan's free space.
file(WRITE ${WORK_DIR}/turned.relations "0.0 0.5 0.25 0 0 0 0 0.07\n")
expect_run(0 relations ${LOG} --relations ${WORK_DIR}/turned.relations --methods contour)
expect_match("${LAST_OUT}" "contour: 0 gross error\\(s\\) [^\n]*; such a reference on 1 of all 1 converged but wrong")

# relations counts the converged pairs whose judge weighed a distinct rival, and on how many the
# rival, not the answer, is the reference's motion: none against the ground truth. Given a
# relation that claims a rival's motion, the count finds it.
expect_run(0 relations ${LOG} --gt ${GT} --methods contour --pairs-csv ${WORK_DIR}/rivals.csv)
expect_match("${LAST_OUT}" "contour: the judge weighed a distinct rival on [1-9][0-9]* of 98 converged pairs; 0 of those rivals lie within the tolerance")
# A converged row ends with the rival and the answer's overlap and score (the score at most the overlap).
file(STRINGS ${WORK_DIR}/rivals.csv rows
     REGEX "^contour,[^\"]*,converged,\"\",.*,-?[0-9.]+,-?[0-9.]+,-?[0-9.]+,[0-9.]+,-?[0-9.]+$")
list(GET rows 0 row)
string(REPLACE "," ";" fields "${row}")
list(GET fields 3 t1)
list(GET fields 4 t2)
list(GET fields 29 rival_x)
list(GET fields 30 rival_y)
list(GET fields 31 rival_yaw)
list(GET fields 32 overlap)
list(GET fields 33 score)
if(score GREATER overlap OR overlap GREATER 1 OR NOT overlap GREATER 0.5)
  message(FATAL_ERROR "relations: overlap ${overlap}, score ${score} in ${row}")
endif()
file(WRITE ${WORK_DIR}/rival.relations "${t1} ${t2} ${rival_x} ${rival_y} 0 0 0 ${rival_yaw}\n")
expect_run(0 relations ${LOG} --relations ${WORK_DIR}/rival.relations --methods contour)
expect_match("${LAST_OUT}" "contour: the judge weighed a distinct rival on 1 of 1 converged pairs; 1 of those rivals lie within the tolerance")

# A relation of another log (stamps far beyond this one's) is left out and counted, not paired
# with the nearest scans.
file(WRITE ${WORK_DIR}/mixed.relations "0.0 0.5 0.25 0 0 0 0 0\n1000001.0 1000002.0 0.5 0 0 0 0 0\n")
expect_run(0 relations ${LOG} --relations ${WORK_DIR}/mixed.relations --methods contour)
expect_match("${LAST_OUT}" ": 1 relations with [^\n]*\n\n1 more relations have no scan within 10 ms of a stamp: left out")
expect_match("${LAST_OUT}" "\\| contour \\| 100.0 % \\| 100.0 % \\| 0.0 % \\|")

# relations on a simulated log, referenced by its ground truth: scans two apart (0.5 m at 2 Hz),
# every one of them recovered.
expect_run(0 relations ${LOG} --gt ${GT} --gt-gap 2 --methods contour)
expect_match("${LAST_OUT}" "97 pairs of scans 2 apart, referenced by [^\n]*L-hokuyo-2hz.gt.tum")
expect_match("${LAST_OUT}" "\\| contour \\| 100.0 % \\| 100.0 % \\| 0.0 % \\|")

# Read with one beam in two (0.5 deg instead of 0.25), the same pairs still register, and the
# header says which scans were measured.
expect_run(0 relations ${LOG} --gt ${GT} --gt-gap 2 --methods contour --beam-step 2)
expect_match("${LAST_OUT}" "L-hokuyo-2hz.clf \\(one beam in 2\\): 97 pairs of scans 2 apart")
expect_match("${LAST_OUT}" "\\| contour \\| 100.0 % \\| 100.0 % \\| 0.0 % \\|")

# relations reports, for each kind of decline, on how many pairs the motion the method declined
# was right. Without special points (threshold 0.99) every pair goes to the contours' own
# hypotheses, and an overlap of 100 % is more than any pair gives (without free space, which lets
# the beams vouch for less): both pairs decline the motion they found, the true 0.25 m ahead,
# right against the first relation and not the second. With free space the beams agree with it.
expect_run(0 relations ${LOG} --relations ${WORK_DIR}/straight.relations --methods contour --threshold 0.99
           --local-fallback 1 --no-free-space --pairs-csv ${WORK_DIR}/declined.csv)
expect_match("${LAST_ERR}" "contour failed: low_overlap: 2; the motion it declined was within the tolerance on 1")
file(STRINGS ${WORK_DIR}/declined.csv rows REGEX "^contour,")
foreach(row IN LISTS rows)
  # The declined motion, then the rival's empty fields and the answer's empty overlap and score:
  # a declined pair has no converged answer to rival or score.
  if(NOT row MATCHES ",low_overlap,.*,(-?[0-9.]+),(-?[0-9.]+),(-?[0-9.]+),,,,,$")
    message(FATAL_ERROR "relations: no declined motion in ${row}")
  endif()
  if(CMAKE_MATCH_1 LESS 0.2 OR CMAKE_MATCH_1 GREATER 0.3)
    message(FATAL_ERROR "relations: declined motion ${CMAKE_MATCH_1} m ahead, not 0.25, in ${row}")
  endif()
endforeach()
expect_run(0 relations ${LOG} --relations ${WORK_DIR}/straight.relations --methods contour --threshold 0.99
           --local-fallback 1)
expect_match("${LAST_OUT}" "\\| contour \\| 50.0 % \\| 100.0 % \\| 50.0 % \\|")

# simulate on a map image, and a path that fits nowhere.
file(WRITE ${WORK_DIR}/paths.txt "# name x y ...\nshort 1 1 3 1\n")
expect_run(0 simulate --map office --paths-file ${WORK_DIR}/paths.txt --path short --out ${WORK_DIR}/short.clf)
file(WRITE ${WORK_DIR}/badpaths.txt "short 1 1 3\n")
expect_run(2 simulate --paths-file ${WORK_DIR}/badpaths.txt --path short --out ${WORK_DIR}/short.clf)
expect_match("${LAST_ERR}" "badpaths.txt:1:")
# The built-in door row and its one path.
expect_run(0 simulate --map doors --path line --rate 0.5 --lidar ydlidar --out ${WORK_DIR}/doors.clf)
expect_match("${LAST_ERR}" "along path line \\(54.0 m\\) in doors")
expect_run(2 simulate --map doors --path S --out ${WORK_DIR}/doors.clf)
expect_match("${LAST_ERR}" "unknown path 'S' in the door row")
expect_run(2 experiment --map ${WORK_DIR}/missing.yaml --out ${WORK_DIR}/experiment2)
expect_match("${LAST_ERR}" "missing.yaml")

# Bad input: a missing file, a file with no scan, an unknown method, an out-of-range scan.
expect_run(2 odometry ${WORK_DIR}/missing.clf --output ${WORK_DIR}/x.tum)
expect_match("${LAST_ERR}" "missing.clf")
file(WRITE ${WORK_DIR}/garbage.clf "not a log\n\x01\x02\n")
expect_run(2 odometry ${WORK_DIR}/garbage.clf --output ${WORK_DIR}/x.tum)
expect_match("${LAST_ERR}" "garbage.clf: no usable scan")
expect_run(2 odometry ${LOG} --method nonsense --output ${WORK_DIR}/x.tum)
expect_run(2 debug ${LOG} --scan 100000 --out ${WORK_DIR}/pictures)
expect_run(2 evaluate ${WORK_DIR}/contour.tum)
expect_match("${LAST_ERR}" "give --gt or --relations")
message(STATUS "cli commands: all checks passed")
