#pragma once
// The definitions (ros2msg text) of the ROS 2 messages the bag writers write: what an MCAP
// schema carries so that a viewer decodes a topic without a ROS installation. Internal to the
// io module.

#include <string>

namespace contour_reg::io::detail {

/// The definition of `type` (e.g. "sensor_msgs/msg/LaserScan") as rosbag2 stores it: the
/// message's fields, then each message it uses after a line of '=' and "MSG: package/Name".
/// "" for a type the writers do not write.
std::string messageDefinition(const std::string &type);

}  // namespace contour_reg::io::detail
