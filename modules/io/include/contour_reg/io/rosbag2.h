#pragma once
/// @file rosbag2.h
/// ROS 2 bags in either of rosbag2's storages, sqlite3 (.db3, the default through ROS 2
/// Humble) and MCAP (.mcap, from Iron on; chunks uncompressed, LZ4 or Zstandard): a bag's
/// folder (its metadata.yaml names the storage files, read in its order) or one storage
/// file, with sensor_msgs/msg/LaserScan (or MultiEchoLaserScan, each beam's first echo its
/// range), nav_msgs/msg/Odometry and tf2_msgs/msg/TFMessage messages in CDR, read with SQLite, zstd and lz4 and no ROS
/// installation. Bags rosbag2 compressed with zstd are read too: file by file (each storage file one zstd frame, named
/// *.db3.zstd or *.mcap.zstd, decompressed into a temporary file) or message by message (each
/// message's bytes a zstd frame); each is told by the zstd magic number of its bytes.
///
/// What is read is what readRosbag reads of a ROS 1 bag: a scan's stamp is its header stamp,
/// its odometry the Odometry pose interpolated at that stamp (or tf's pose of the robot in
/// "odom" in a bag without Odometry), its beam timing the message's
/// time_increment, the laser's mounting the first scan's frame in the odometry's child frame
/// (base_link without odometry) through the TFMessage topics' first transforms of each
/// frame. A message that cannot be decoded is skipped and reported with its file, topic and
/// index (a compressed one that does not decompress too); an MCAP chunk that cannot be read (it does not decompress or
/// match its CRC) with its file and byte, and its messages are not read.

#include <string>

#include "contour_reg/io/rosbag.h"
#include "contour_reg/io/scan_log.h"

namespace contour_reg::io {

/// Whether `path` is a ROS 2 bag by its name: a .db3 or .mcap file (.zstd after it: compressed),
/// or a folder with a metadata.yaml or such a file in it.
bool isRosbag2(const std::string &path);

/// Reads the scans and odometry of a ROS 2 bag. Throws ReadError naming the file when it
/// cannot be opened or is not a bag, an MCAP or compressed file is cut short, the metadata names
/// a compression other than zstd, the bag has no scan topic, or does not carry a topic the
/// options name (with the message type it needs).
ScanLog readRosbag2(const std::string &path, const RosbagOptions &options = {});

/// Writes the log as one storage file of a ROS 2 bag: MCAP for a `path` ending in .mcap
/// (Zstandard chunks, each schema with its message definition, by which viewers such as
/// Foxglove decode the topics, and a summary section that indexes every message by channel and
/// time, where readers that seek start), sqlite3 otherwise (conventionally *.db3). The
/// topics and frames are those writeRosbag gives a ROS 1 bag: /scan (sensor_msgs/msg/LaserScan,
/// frame "laser"), /odom (nav_msgs/msg/Odometry, "odom" -> "base_link") and, with a mounting,
/// /tf_static (tf2_msgs/msg/TFMessage, "base_link" -> "laser"). Throws ReadError naming the file
/// when it cannot be written or a stamp is negative.
void writeRosbag2(const std::string &path, const ScanLog &log);

}  // namespace contour_reg::io
