#pragma once
// What the ROS 1 and ROS 2 bag readers share: sensor_msgs' LaserScan as both define it, how a
// scan message becomes a log entry (or a reported problem), and the static transforms that
// give the laser's mounting. Internal to the io module.

#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "contour_reg/io/pose2d.h"
#include "contour_reg/io/scan_log.h"

namespace contour_reg::io::detail {

/// sensor_msgs/LaserScan (ROS 1) and sensor_msgs/msg/LaserScan (ROS 2): the same fields.
struct ScanMessage {
  double stamp = 0.0;  ///< s, the header's: the first beam's time
  std::string frame_id;
  float angle_min = 0.0f, angle_max = 0.0f, angle_increment = 0.0f;
  float time_increment = 0.0f, scan_time = 0.0f;
  float range_min = 0.0f, range_max = 0.0f;
  std::vector<float> ranges;
};

/// Appends `message` to `log` as a scan (ranges outside [range_min, min(range_max,
/// max_range)) as NaN, the beam timing when it can be used), or reports at `where`, message
/// `index`, why it cannot be read or why its timing is dropped. True when a scan was added.
bool addScan(const ScanMessage &message, double max_range, std::size_t max_beams, const std::string &where,
             std::size_t index, ScanLog &log);

/// `scan` as a LIDAR driver publishes it: frame "laser", angle_max the last beam's bearing,
/// scan_time one turn of beams time_increment apart (0 without timing), invalid beams +inf, and
/// range_max the scan's or, without one, just above its farthest return.
ScanMessage scanMessageOf(const LaserScan &scan);

/// A beam's range from its echoes (sensor_msgs' LaserEcho): the first, as the strongest or
/// nearest return a multi-echo LIDAR gives first; NaN (no return) without one.
float firstEcho(const std::vector<float> &echoes);

/// A frame's name without a leading '/' (ROS 1's tf accepted both).
std::string frameName(std::string name);

/// The yaw of a unit quaternion (x, y, z, w).
double yawOfQuaternion(double x, double y, double z, double w);

/// A bag's tf tree, planar part: the transforms that do not move (each child frame's first pose
/// in its parent), and the wheel odometry tf carries, the poses of the children of the
/// odometry frame "odom" (REP 105) over time.
class TransformTree {
 public:
  /// Keeps `child`'s pose in `parent` unless the child has one already or it is not finite; a
  /// finite pose of a child of "odom" is also kept as that child's odometry at `stamp` (s).
  void add(const std::string &parent, const std::string &child, const Pose2D &child_in_parent, double stamp);
  /// `frame`'s pose in `base`, through its chain of parents; none when the chain does not reach it.
  std::optional<Pose2D> poseIn(const std::string &base, std::string frame) const;
  /// The odometry tf gives the robot that carries `scan_frame`: the child of "odom" whose chain of
  /// children reaches it (or the only child of "odom"), with its poses over time; none without.
  std::optional<std::pair<std::string, std::vector<StampedPose>>> odometryOf(const std::string &scan_frame) const;

 private:
  std::map<std::string, std::pair<std::string, Pose2D>> parent_of_;  // child -> (parent, child in parent)
  std::map<std::string, std::vector<StampedPose>> odometry_of_;      // child of "odom" -> its poses
};

/// What both bag readers do after the last message: a log without a usable scan is an error
/// naming `path`; without `odometry` (no Odometry topic), the odometry is what tf gives
/// (TransformTree::odometryOf) and its child frame the base frame; the laser's mounting is the
/// first scan's frame (`scan_frame`) in the odometry's child frame (`base_frame`, "base_link"
/// when empty) through `tree`; then the scans are put in stamp order with the odometry at their
/// stamps (finishLog).
void finishBagLog(const std::string &path, const TransformTree &tree, const std::string &scan_frame,
                  const std::string &base_frame, std::vector<StampedPose> odometry, ScanLog &log);

}  // namespace contour_reg::io::detail
