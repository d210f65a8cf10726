#pragma once
// What every reader does after parsing: stamp order and odometry per scan.
// Internal to the io module.

#include <vector>

#include "contour_reg/io/scan_log.h"

namespace contour_reg::io::detail {

/// Odometry at `stamp`, linearly interpolated between the samples around it (yaw along
/// the shorter arc); nothing outside their span. `samples` must be in stamp order.
std::optional<Pose2D> interpolatePose(const std::vector<StampedPose> &samples, double stamp);

/// Puts the scans in stamp order (counting those that were not), keeps `odometry` in stamp
/// order as the log's wheel odometry and gives every scan without odometry the odometry
/// interpolated from it at its stamp.
void finishLog(ScanLog &log, std::vector<StampedPose> odometry);

/// The odometry a writer writes for `log`, in stamp order: its wheel_odometry samples, or the
/// scans' own odometry when it keeps none.
std::vector<StampedPose> odometryToWrite(const ScanLog &log);

}  // namespace contour_reg::io::detail
