#pragma once
/// @file rosbag.h
/// ROS 1 bags (format 2.0, plain, BZ2 or LZ4 chunks) with sensor_msgs/LaserScan (or
/// MultiEchoLaserScan, each beam's first echo its range), nav_msgs/Odometry and
/// tf2_msgs/TFMessage messages, read through Debian's rosbag_storage library.
///
/// A scan's stamp is its header stamp; its odometry is the Odometry pose interpolated at
/// that stamp or, in a bag without an Odometry topic, the pose tf gives the robot in "odom"
/// (REP 105: the transforms from "odom" to the frame that carries the laser). Ranges outside [range_min, min(range_max,
/// max_range)) become NaN. The beam timing is the message's time_increment (LaserScan::time_increment; sensor_msgs'
/// stamp is the first beam's time); a negative one, or one whose sweep is longer than scan_time, is reported and the
/// scan read without timing. The laser's mounting (ScanLog::laser_pose) is the pose of the first scan's frame in the
/// odometry's child frame (base_link when the bag has no odometry at all), through the chain of the tf2_msgs/TFMessage
/// topics' transforms (each frame's first). A message that cannot be decoded is skipped and reported with its topic and
/// index.

#include <string>

#include "contour_reg/io/scan_log.h"

namespace contour_reg::io {

struct RosbagOptions {
  std::string scan_topic;      ///< "": the first topic carrying sensor_msgs/LaserScan, else MultiEchoLaserScan
  std::string odometry_topic;  ///< "": the first topic carrying nav_msgs/Odometry
  double max_range = 40.0;     ///< m
  std::size_t max_beams = 100000;
};

/// True when this build can read bags (the ROS bag library was found at build time).
bool rosbagSupported();

/// Reads the scans and odometry of a bag. Throws ReadError naming the file when it
/// cannot be opened or decoded, has no scan topic, does not carry a topic the options name
/// (with the message type it needs), or this build cannot read bags.
ScanLog readRosbag(const std::string &path, const RosbagOptions &options = {});

/// Writes the log as a ROS 1 bag the way a LIDAR driver and a robot base record one: every
/// scan a sensor_msgs/LaserScan on /scan (frame "laser"; stamp = first beam, time_increment
/// and scan_time = one turn of the LIDAR, range_max the largest finite range; invalid beams +inf), and
/// every odometry pose a nav_msgs/Odometry on /odom ("odom" -> "base_link") at the scan's
/// stamp, and the mounting, when the log has one, on /tf_static ("base_link" -> "laser"). Throws ReadError naming the
/// file when it cannot be written or this build has no bag support.
void writeRosbag(const std::string &path, const ScanLog &log);

}  // namespace contour_reg::io
