#pragma once
/// @file scan_log.h
/// A log of scans with per-scan odometry, as the readers produce it.

#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "contour_reg/core/laser_scan.h"

namespace contour_reg::io {

/// A planar pose: x, y in metres, yaw in radians.
struct Pose2D {
  double x = 0.0, y = 0.0, yaw = 0.0;
};

/// A pose at a stamp (s).
struct StampedPose {
  double stamp = 0.0;
  Pose2D pose;
};

/// One scan of a log and the wheel odometry at its stamp, when the log has it.
struct LogEntry {
  LaserScan scan;
  std::optional<Pose2D> odometry;
};

/// What a reader met besides good lines: skipped lines are counted, the first few described.
struct ReadReport {
  std::size_t lines = 0;              ///< lines read
  std::size_t skipped = 0;            ///< bad or truncated lines skipped
  std::size_t reordered = 0;          ///< scans whose stamp went backwards in file order
  std::vector<std::string> problems;  ///< "file:line: what", the first kFirstProblems and those always shown

  static constexpr std::size_t kFirstProblems = 20;
  enum Shown { kIfAmongTheFirst, kAlwaysShown };
  /// Counts a skipped line and keeps "where:line: what" among the problems, if among the first
  /// kFirstProblems or `shown` is kAlwaysShown (what loses the rest of a file).
  void add(const std::string &where, std::size_t line, const std::string &what, Shown shown = kIfAmongTheFirst);
};

struct ScanLog {
  std::string source;
  std::vector<LogEntry> entries;  ///< in stamp order
  /// Every wheel odometry sample of the log (CARMEN ODOM lines, nav_msgs/Odometry messages), in
  /// stamp order, the robot's pose in the odometry frame. A robot logs these faster than its
  /// scans; a scan's `odometry` is interpolated from them. May be empty when the scans carry
  /// their odometry themselves.
  std::vector<StampedPose> wheel_odometry;
  ReadReport report;
  /// The laser's pose in the robot's frame (base_link -> laser), when the log says where the
  /// laser is mounted: scans are in the laser's frame, odometry is the robot's.
  std::optional<Pose2D> laser_pose;
};

/// m: no robot carries its LIDAR further from its base_link. A log that mounts it further
/// (a corrupt ROBOTLASER1 line or transform) is an error (readLog).
inline constexpr double kFarthestMounting = 100.0;

/// Whether `pose` can be a laser's mounting on a robot: finite, within kFarthestMounting of
/// base_link, turned by at most a whole turn.
inline bool isMounting(const Pose2D &pose) {
  return std::isfinite(pose.x + pose.y + pose.yaw) && std::hypot(pose.x, pose.y) <= kFarthestMounting &&
         std::abs(pose.yaw) <= 2.0 * M_PI;
}

/// Thrown when a file cannot be used at all (missing, unreadable, no usable scan).
class ReadError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace contour_reg::io
