#pragma once
/// @file rosbag.h
/// ROS 1 bags (format 2.0, plain, BZ2 or LZ4 chunks) with sensor_msgs/LaserScan and
/// nav_msgs/Odometry messages, read through Debian's rosbag_storage library.
///
/// A scan's stamp is its header stamp; its odometry is the Odometry pose interpolated at
/// that stamp. Ranges outside [range_min, min(range_max, max_range)) become NaN. A message
/// that cannot be decoded is skipped and reported with its topic and index.

#include <string>

#include "contour_reg/io/scan_log.h"

namespace contour_reg::io {

struct RosbagOptions {
  std::string scan_topic;      ///< "": the first topic carrying sensor_msgs/LaserScan
  std::string odometry_topic;  ///< "": the first topic carrying nav_msgs/Odometry
  double max_range = 40.0;     ///< m
  std::size_t max_beams = 100000;
};

/// True when this build can read bags (the ROS bag library was found at build time).
bool rosbagSupported();

/// Reads the scans and odometry of a bag. Throws ReadError naming the file when it
/// cannot be opened or decoded, has no scan topic, or this build cannot read bags.
ScanLog readRosbag(const std::string &path, const RosbagOptions &options = {});

}  // namespace contour_reg::io
