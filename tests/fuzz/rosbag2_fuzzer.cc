// libFuzzer target: arbitrary bytes as a message of a ROS 2 bag (sqlite3 storage). The first
// byte picks the topic (a LaserScan, an Odometry, a TFMessage or a MultiEchoLaserScan, read as
// the scan topic it names), the rest is the message's CDR.
// The reader must return scans or throw io::ReadError, whatever the message declares.
#include <sqlite3.h>

#include <cstddef>
#include <cstdint>
#include <string>

#include <unistd.h>

#include "contour_reg/io/rosbag2.h"

namespace {

// A bag with the three topics; each input is its one message.
sqlite3 *openBag(const std::string &path) {
  unlink(path.c_str());
  sqlite3 *db = nullptr;
  if (sqlite3_open(path.c_str(), &db) != SQLITE_OK) return nullptr;
  sqlite3_exec(db,
               "CREATE TABLE topics(id INTEGER PRIMARY KEY, name TEXT NOT NULL, type TEXT NOT NULL,"
               " serialization_format TEXT NOT NULL, offered_qos_profiles TEXT NOT NULL);"
               "CREATE TABLE messages(id INTEGER PRIMARY KEY, topic_id INTEGER NOT NULL, timestamp INTEGER NOT NULL,"
               " data BLOB NOT NULL);"
               "INSERT INTO topics VALUES(1, '/scan', 'sensor_msgs/msg/LaserScan', 'cdr', '');"
               "INSERT INTO topics VALUES(2, '/odom', 'nav_msgs/msg/Odometry', 'cdr', '');"
               "INSERT INTO topics VALUES(3, '/tf', 'tf2_msgs/msg/TFMessage', 'cdr', '');"
               "INSERT INTO topics VALUES(4, '/echoes', 'sensor_msgs/msg/MultiEchoLaserScan', 'cdr', '');",
               nullptr, nullptr, nullptr);
  return db;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size) {
  static const std::string path = "/tmp/contour_reg_fuzz_" + std::to_string(getpid()) + ".db3";
  static sqlite3 *db = openBag(path);
  if (!db || size == 0) return 0;
  sqlite3_exec(db, "DELETE FROM messages;", nullptr, nullptr, nullptr);
  sqlite3_stmt *insert = nullptr;
  sqlite3_prepare_v2(db, "INSERT INTO messages(topic_id, timestamp, data) VALUES(?, 0, ?)", -1, &insert, nullptr);
  const int topic = 1 + data[0] % 4;
  sqlite3_bind_int(insert, 1, topic);
  sqlite3_bind_blob(insert, 2, data + 1, static_cast<int>(size - 1), SQLITE_STATIC);
  sqlite3_step(insert);
  sqlite3_finalize(insert);
  try {
    contour_reg::io::RosbagOptions options;
    if (topic == 4) options.scan_topic = "/echoes";
    (void)contour_reg::io::readRosbag2(path, options);
  } catch (const contour_reg::io::ReadError &) {
  }
  return 0;
}
