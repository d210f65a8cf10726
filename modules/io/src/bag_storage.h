#pragma once
// What rosbag2's two storages, sqlite3 (sqlite_storage.h) and MCAP (mcap.h), hold for a
// reader of ROS 2 bags: topics with their message type, and messages of CDR bytes. Internal to
// the io module.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace contour_reg::io::detail {

/// A topic (an MCAP channel) and its message type, e.g. sensor_msgs/msg/LaserScan.
struct StoredTopic {
  std::uint16_t id = 0;
  std::string name, message_encoding;
  std::string type;  ///< "" without a schema
};

/// A message to write: `topic` indexes the topics written.
struct StoredMessage {
  std::size_t topic = 0;
  std::uint64_t log_time = 0;  ///< ns
  std::vector<std::uint8_t> data;
};

/// What a storage's reader hands over, in the file's order.
struct StorageVisitor {
  /// A topic, before any of its messages.
  std::function<void(const StoredTopic &)> topic;
  /// A message of the topic with that id, and its bytes.
  std::function<void(std::uint16_t topic, const std::uint8_t *data, std::size_t size)> message;
  /// Messages lost at `byte` of the file (an MCAP chunk that cannot be read), and why.
  std::function<void(std::uint64_t byte, const std::string &why)> lost;
};

}  // namespace contour_reg::io::detail
