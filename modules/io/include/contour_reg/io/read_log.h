#pragma once
/// @file read_log.h
/// One entry point for every scan source: a CARMEN log (`.clf`, `.log`, `.gz`, anything
/// else), a ROS 1 bag (`.bag`), a ROS 2 bag (its folder, or a `.db3` or `.mcap` file, either
/// compressed by rosbag2 as `.zstd`) or a folder of PCD scans (a directory).

#include <optional>
#include <string>

#include "contour_reg/io/scan_log.h"

namespace contour_reg::io {

struct LogReadOptions {
  double max_range = 40.0;         ///< m, readings at or above are no-return
  std::size_t max_beams = 100000;  ///< scans announcing more beams are rejected
  std::string scan_topic;          ///< bags: the LaserScan topic ("": the first one)
  std::string odometry_topic;      ///< bags: the Odometry topic ("": the first one)
  /// s per turn of a spinning LIDAR, for scans that carry no beam timing of their own (CARMEN
  /// lines and PCD files never do): beams are then taken in index order (counter-clockwise,
  /// as sensor_msgs orders them) scan_period * angle_increment / 2 pi apart, the first at the
  /// scan's stamp (LaserScan::time_increment). 0: no timing.
  double scan_period = 0.0;
  /// s: no spinning LIDAR turns slower.
  static constexpr double kLongestScanPeriod = 10.0;
  /// The laser's pose on the robot (base_link -> laser; x, y in m, yaw in rad), over what the
  /// log says (ScanLog::laser_pose: ROBOTLASER1 lines, a bag's tf).
  std::optional<Pose2D> laser_pose;
  /// Keeps every beam_step-th beam, from the first: the scans a LIDAR with beam_step times the
  /// angular step (and time between beams) would give, to study angular resolution on logs
  /// with finer beams. 1: every beam. Must be >= 1.
  std::size_t beam_step = 1;
  /// false: the log's wheel odometry (and the poses its scan lines carry) is left out, the
  /// scans read alone, as a LIDAR without wheels gives them.
  bool wheel_odometry = true;
};

/// Reads `path` with the reader its kind calls for, then gives scans without beam timing
/// the timing of `scan_period`, the log the mounting `laser_pose` when set, and leaves the
/// wheel odometry out without `wheel_odometry`, and keeps every `beam_step`-th beam. Throws
/// ReadError naming the file (a log that mounts the laser where io::isMounting says no robot
/// does among its reasons), std::invalid_argument for options out of range: max_range not
/// above 0, scan_period outside 0-kLongestScanPeriod, beam_step 0, a laser_pose that is no
/// mounting.
ScanLog readLog(const std::string &path, const LogReadOptions &options = {});

/// Leaves the log's wheel odometry (and the poses its scan lines carry) out: the scans alone,
/// as LogReadOptions::wheel_odometry = false reads them.
void leaveOutWheelOdometry(ScanLog &log);

/// The index of the entry whose scan stamp is nearest `stamp` (s); the later one on a tie.
/// `log` must have an entry.
std::size_t nearestEntry(const ScanLog &log, double stamp);

/// Writes `log` in the format its name asks for: a ROS 1 bag (.bag), a ROS 2 bag's storage
/// file (.db3: sqlite3, .mcap: MCAP) or a CARMEN log (any other name but *.zstd, which
/// is refused). Throws ReadError naming the file when it cannot be written.
void writeLog(const std::string &path, const ScanLog &log);

}  // namespace contour_reg::io
