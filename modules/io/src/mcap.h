#pragma once
// MCAP files (https://mcap.dev/spec, version 0), the storage of ROS 2 bags from ROS 2 Iron on:
// the records of the data section in file order, chunks uncompressed, LZ4 or Zstandard
// decompressed in turn. Every record's length is checked against what holds it before it is
// read. Internal to the io module.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace contour_reg::io::detail {

struct McapChannel {
  std::uint16_t id = 0;
  std::string topic, message_encoding;
  std::string schema_name;  ///< the message type, e.g. sensor_msgs/msg/LaserScan ("" without a schema)
};

struct McapVisitor {
  /// A channel, before any of its messages.
  std::function<void(const McapChannel &)> channel;
  /// A message's channel id and bytes.
  std::function<void(std::uint16_t channel, const std::uint8_t *data, std::size_t size)> message;
  /// A chunk that cannot be read (`byte`: its offset in the file): its messages are not visited.
  std::function<void(std::uint64_t byte, const std::string &why)> unreadable_chunk;
};

/// Visits the channels and messages of the MCAP file at `path`. Throws ReadError naming the
/// file (and the byte) when it is not an MCAP file or a record does not fit in the file.
void visitMcap(const std::string &path, const McapVisitor &visitor);

struct McapMessage {
  std::size_t channel = 0;     ///< index into the channels written
  std::uint64_t log_time = 0;  ///< ns
  std::vector<std::uint8_t> data;
};

/// Writes an MCAP file of the ros2 profile: each channel with a schema named by its type
/// (encoding ros2msg, its definition text left empty: readers of ROS 2 bags go by the name),
/// the messages in chunks of up to 1 MB compressed with `compression` ("", "lz4" or "zstd"),
/// then the data end and footer records. Throws ReadError naming the file when it cannot be written.
void writeMcap(const std::string &path, const std::vector<McapChannel> &channels,
               const std::vector<McapMessage> &messages, const std::string &compression);

}  // namespace contour_reg::io::detail
