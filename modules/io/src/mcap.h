#pragma once
// MCAP files (https://mcap.dev/spec, version 0), the storage of ROS 2 bags from ROS 2 Iron on:
// the records of the data section in file order, chunks uncompressed, LZ4 or Zstandard
// decompressed in turn. Every record's length is checked against what holds it before it is
// read. Internal to the io module.

#include <string>
#include <vector>

#include "bag_storage.h"

namespace contour_reg::io::detail {

/// Visits the channels (topics) and messages of the MCAP file at `path`. Throws ReadError naming the
/// file (and the byte) when it is not an MCAP file or a record does not fit in the file.
void visitMcap(const std::string &path, const StorageVisitor &visitor);

/// Writes an MCAP file of the ros2 profile: each channel with a schema named by its type
/// (encoding ros2msg, with the definition text of message_definitions.h, by which a viewer
/// decodes the messages; ROS 2 bag readers go by the name),
/// the messages in chunks of up to 1 MB compressed with `compression` ("", "lz4" or "zstd"),
/// each chunk followed by the index of each channel's messages in it (log time, offset), then
/// the data end, the summary section (schemas, channels, statistics, each chunk's index) and
/// the footer that points to it, where a reader that seeks starts.
/// Throws ReadError naming the file when it cannot be written.
void writeMcap(const std::string &path, const std::vector<StoredTopic> &topics,
               const std::vector<StoredMessage> &messages, const std::string &compression);

}  // namespace contour_reg::io::detail
