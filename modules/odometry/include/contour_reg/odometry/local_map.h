#pragma once
/// @file local_map.h
/// A local map of the last few keyframes, as one scan. Local-map odometry (KISS-ICP's local
/// map, Cartographer's submaps) matches a new scan against more than the scan before it: more
/// structure for sparse scans, less drift. The contour method needs a scan (beams in bearing
/// order), so the map is drawn as the scan a full-turn LIDAR at the newest keyframe would take
/// of it: the newest keyframe's own beams, then, in the bearings it left empty (no return,
/// behind a LIDAR of less than a full turn), the returns of the older keyframes, newer first.

#include <vector>

#include "contour_reg/core/deskew.h"
#include "contour_reg/core/laser_scan.h"
#include "contour_reg/io/scan_log.h"

namespace contour_reg::odometry {

/// A keyframe of the map: its scan, the sensor's motion over the scan's sweep (deskew.h),
/// and the scan's pose in the odometry frame.
struct MapKeyframe {
  const LaserScan *scan = nullptr;
  SweepMotion motion;
  io::Pose2D pose;
};

/// The map of `keyframes` (oldest first, the newest last) seen from the newest: a full turn of
/// beams at the newest scan's angle increment, aligned with its beams, stamped as it is.
/// Empty keyframes give an empty scan.
LaserScan renderLocalMap(const std::vector<MapKeyframe> &keyframes);

}  // namespace contour_reg::odometry
