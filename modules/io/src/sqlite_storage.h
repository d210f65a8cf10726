#pragma once
// rosbag2's sqlite3 storage (.db3, the default through ROS 2 Humble): a table of topics (name,
// type, serialization) and one of messages (topic, time, CDR bytes), read and written with
// SQLite. Internal to the io module.

#include <string>
#include <vector>

#include "bag_storage.h"

namespace contour_reg::io::detail {

/// Visits the topics, then the messages in time order, of the .db3 file at `path`. Throws
/// ReadError naming the file when it cannot be opened or is not a bag.
void visitSqlite(const std::string &path, const StorageVisitor &visitor);

/// Writes `messages` of `topics` as a .db3 file with rosbag2's schema (version 3, ROS 2
/// Humble), replacing any file at `path`. Throws ReadError naming the file when it cannot.
void writeSqlite(const std::string &path, const std::vector<StoredTopic> &topics,
                 const std::vector<StoredMessage> &messages);

}  // namespace contour_reg::io::detail
