#pragma once
// What every reader does after parsing: stamp order and odometry per scan.
// Internal to the io module.

#include <vector>

#include "contour_reg/io/scan_log.h"

namespace contour_reg::io::detail {

/// An odometry sample of a log (CARMEN ODOM line, nav_msgs/Odometry message).
struct TimedPose {
  double stamp = 0.0;
  Pose2D pose;
};

/// Odometry at `stamp`, linearly interpolated between the samples around it (yaw along
/// the shorter arc); nothing outside their span. `samples` must be in stamp order.
std::optional<Pose2D> interpolatePose(const std::vector<TimedPose> &samples, double stamp);

/// Puts the scans in stamp order (counting those that were not) and gives every scan
/// without odometry the odometry interpolated from `odometry` at its stamp.
void finishLog(ScanLog &log, std::vector<TimedPose> odometry);

}  // namespace contour_reg::io::detail
