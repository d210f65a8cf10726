#include <sqlite3.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "contour_reg/io/read_log.h"
#include "contour_reg/io/rosbag2.h"
#include "temp_dir.h"
#include "timed_log.h"

namespace contour_reg::io {
namespace {

using test::timedLog;

// Bytes laid out by hand at the offsets the CDR rules give (a field aligned to its size,
// counted after the 4-byte encapsulation header), independent of the library's writer.
class Bytes {
 public:
  explicit Bytes(bool little_endian = true) : little_(little_endian), bytes_{0x00, 0x00, 0x00, 0x00} {
    bytes_[1] = little_endian ? 0x01 : 0x00;  // the encapsulation: CDR, little or big endian
  }
  // Puts `value` at `offset` past the encapsulation header, zeros before it.
  template <typename T>
  Bytes &at(std::size_t offset, T value) {
    unsigned char raw[sizeof(T)];
    std::memcpy(raw, &value, sizeof(T));
    if (!little_)
      for (std::size_t k = 0; k < sizeof(T) / 2; ++k) std::swap(raw[k], raw[sizeof(T) - 1 - k]);
    place(offset, raw, sizeof(T));
    return *this;
  }
  Bytes &text(std::size_t offset, const std::string &chars) {  // the characters and their NUL
    place(offset, reinterpret_cast<const unsigned char *>(chars.c_str()), chars.size() + 1);
    return *this;
  }
  std::vector<std::uint8_t> data() const { return bytes_; }

 private:
  void place(std::size_t offset, const unsigned char *raw, std::size_t size) {
    if (bytes_.size() < 4 + offset + size) bytes_.resize(4 + offset + size, 0);
    std::memcpy(bytes_.data() + 4 + offset, raw, size);
  }
  bool little_;
  std::vector<std::uint8_t> bytes_;
};

// sensor_msgs/msg/LaserScan: stamp 12.25 s, frame "laser" (6 bytes with its NUL, ending at 18,
// so the first float is padded to 20), three ranges.
std::vector<std::uint8_t> handMadeScan(bool little_endian = true, std::uint32_t declared_ranges = 3) {
  Bytes b(little_endian);
  b.at<std::int32_t>(0, 12).at<std::uint32_t>(4, 250000000u).at<std::uint32_t>(8, 6).text(12, "laser");
  b.at<float>(20, -1.5f).at<float>(24, -0.5f).at<float>(28, 0.5f);  // angle_min, angle_max, angle_increment
  b.at<float>(32, 0.001f).at<float>(36, 0.1f);                      // time_increment, scan_time
  b.at<float>(40, 0.1f).at<float>(44, 20.0f);                       // range_min, range_max
  b.at<std::uint32_t>(48, declared_ranges).at<float>(52, 1.0f).at<float>(56, 25.0f).at<float>(60, 3.0f);
  b.at<std::uint32_t>(64, 0);  // no intensities
  return b.data();
}

// nav_msgs/msg/Odometry at `stamp_s`, "odom" -> "base_link": the child's name ends at 34, so
// the position's float64 is padded to 40. Pose x `x`, y -2, yaw 90 deg.
std::vector<std::uint8_t> handMadeOdometry(double stamp_s, double x) {
  Bytes b;
  b.at<std::int32_t>(0, static_cast<std::int32_t>(stamp_s))
      .at<std::uint32_t>(4, 0)
      .at<std::uint32_t>(8, 5)
      .text(12, "odom");
  b.at<std::uint32_t>(20, 10).text(24, "base_link");
  b.at<double>(40, x).at<double>(48, -2.0).at<double>(56, 0.0);
  b.at<double>(64, 0.0).at<double>(72, 0.0).at<double>(80, std::sqrt(0.5)).at<double>(88, std::sqrt(0.5));
  b.at<double>(96 + 8 * 77, 0.0);  // covariance, twist, twist covariance: zeros
  return b.data();
}

// tf2_msgs/msg/TFMessage with one transform "base_link" -> "laser", 0.2 m ahead, turned 180 deg.
std::vector<std::uint8_t> handMadeMounting() {
  Bytes b;
  b.at<std::uint32_t>(0, 1).at<std::int32_t>(4, 12).at<std::uint32_t>(8, 0);
  b.at<std::uint32_t>(12, 10).text(16, "base_link");  // ends at 26
  b.at<std::uint32_t>(28, 6).text(32, "laser");       // ends at 38; doubles from 40
  b.at<double>(40, 0.2).at<double>(48, 0.0).at<double>(56, 0.0);
  b.at<double>(64, 0.0).at<double>(72, 0.0).at<double>(80, 1.0).at<double>(88, 0.0);
  return b.data();
}

struct Message {
  int topic;
  std::int64_t stamp_ns;
  std::vector<std::uint8_t> data;
};

// A .db3 file with rosbag2's sqlite3 schema, written with SQLite directly.
void writeDb3(const std::string &path, const std::vector<Message> &messages) {
  sqlite3 *db = nullptr;
  ASSERT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
  ASSERT_EQ(sqlite3_exec(db,
                         "CREATE TABLE topics(id INTEGER PRIMARY KEY, name TEXT NOT NULL, type TEXT NOT NULL,"
                         " serialization_format TEXT NOT NULL, offered_qos_profiles TEXT NOT NULL);"
                         "CREATE TABLE messages(id INTEGER PRIMARY KEY, topic_id INTEGER NOT NULL,"
                         " timestamp INTEGER NOT NULL, data BLOB NOT NULL);"
                         "INSERT INTO topics VALUES(7, '/front/scan', 'sensor_msgs/msg/LaserScan', 'cdr', '');"
                         "INSERT INTO topics VALUES(8, '/wheel/odom', 'nav_msgs/msg/Odometry', 'cdr', '');"
                         "INSERT INTO topics VALUES(9, '/tf_static', 'tf2_msgs/msg/TFMessage', 'cdr', '');"
                         "INSERT INTO topics VALUES(10, '/chatter', 'std_msgs/msg/String', 'cdr', '');",
                         nullptr, nullptr, nullptr),
            SQLITE_OK);
  sqlite3_stmt *insert = nullptr;
  ASSERT_EQ(
      sqlite3_prepare_v2(db, "INSERT INTO messages(topic_id, timestamp, data) VALUES(?, ?, ?)", -1, &insert, nullptr),
      SQLITE_OK);
  for (const Message &m : messages) {
    sqlite3_reset(insert);
    sqlite3_bind_int(insert, 1, m.topic);
    sqlite3_bind_int64(insert, 2, m.stamp_ns);
    sqlite3_bind_blob(insert, 3, m.data.data(), static_cast<int>(m.data.size()), SQLITE_TRANSIENT);
    ASSERT_EQ(sqlite3_step(insert), SQLITE_DONE);
  }
  sqlite3_finalize(insert);
  sqlite3_close(db);
}

TEST(Rosbag2, HandLaidMessagesReadAsTheirFieldsSay) {
  test::TempDir dir;
  const std::string path = dir.file("hand.db3");
  writeDb3(path, {{9, 11'000'000'000, handMadeMounting()},
                  {8, 12'000'000'000, handMadeOdometry(12.0, 1.5)},
                  {10, 12'100'000'000, {0, 1, 0, 0, 1, 0, 0, 0, 0}},
                  {7, 12'250'000'000, handMadeScan()},
                  {8, 13'000'000'000, handMadeOdometry(13.0, 2.5)}});
  const ScanLog log = readLog(path);
  EXPECT_TRUE(log.report.problems.empty()) << log.report.problems.front();
  ASSERT_EQ(log.entries.size(), 1u);
  const LaserScan &scan = log.entries[0].scan;
  EXPECT_DOUBLE_EQ(scan.stamp, 12.25);
  EXPECT_FLOAT_EQ(static_cast<float>(scan.angle_min), -1.5f);
  EXPECT_FLOAT_EQ(static_cast<float>(scan.angle_increment), 0.5f);
  EXPECT_FLOAT_EQ(static_cast<float>(scan.time_increment), 0.001f);
  ASSERT_EQ(scan.ranges.size(), 3u);
  EXPECT_FLOAT_EQ(scan.ranges[0], 1.0f);
  EXPECT_TRUE(std::isnan(scan.ranges[1])) << "25 m is beyond range_max 20 m";
  EXPECT_FLOAT_EQ(scan.ranges[2], 3.0f);
  // The odometry at the scan's stamp: a quarter of the way from x 1.5 to 2.5.
  ASSERT_TRUE(log.entries[0].odometry.has_value());
  EXPECT_NEAR(log.entries[0].odometry->x, 1.75, 1e-9);
  EXPECT_NEAR(log.entries[0].odometry->y, -2.0, 1e-9);
  EXPECT_NEAR(log.entries[0].odometry->yaw, M_PI / 2, 1e-9);
  ASSERT_EQ(log.wheel_odometry.size(), 2u);
  // The mounting: the scan's frame "laser" in the odometry's child frame "base_link".
  ASSERT_TRUE(log.laser_pose.has_value());
  EXPECT_NEAR(log.laser_pose->x, 0.2, 1e-12);
  EXPECT_NEAR(std::abs(log.laser_pose->yaw), M_PI, 1e-12);
}

TEST(Rosbag2, ABigEndianMessageReadsTheSame) {
  test::TempDir dir;
  const std::string path = dir.file("big.db3");
  writeDb3(path, {{7, 12'250'000'000, handMadeScan(false)}});
  const ScanLog log = readLog(path);
  ASSERT_EQ(log.entries.size(), 1u);
  EXPECT_DOUBLE_EQ(log.entries[0].scan.stamp, 12.25);
  ASSERT_EQ(log.entries[0].scan.ranges.size(), 3u);
  EXPECT_FLOAT_EQ(log.entries[0].scan.ranges[2], 3.0f);
}

TEST(Rosbag2, AScanThatDeclaresMoreRangesThanItHoldsIsSkippedAndNamed) {
  test::TempDir dir;
  const std::string path = dir.file("short.db3");
  writeDb3(path, {{7, 12'250'000'000, handMadeScan(true, 0x7fffffff)}, {7, 12'350'000'000, handMadeScan()}});
  const ScanLog log = readLog(path);
  EXPECT_EQ(log.entries.size(), 1u);
  ASSERT_EQ(log.report.problems.size(), 1u);
  const std::string &problem = log.report.problems.front();
  EXPECT_NE(problem.find(path + " (/front/scan):1"), std::string::npos) << problem;
  EXPECT_NE(problem.find("longer than the message"), std::string::npos) << problem;
}

TEST(Rosbag2, AWrittenBagReadsBackWithBeamTimingOdometryAndMounting) {
  test::TempDir dir;
  const std::string path = dir.file("timed.db3");
  ScanLog written = timedLog();
  written.laser_pose = Pose2D{0.3, -0.1, 0.25};
  writeRosbag2(path, written);
  const ScanLog read = readLog(path);
  test::expectTimedLogReadBack(read, written);
  ASSERT_TRUE(read.laser_pose.has_value());
  EXPECT_NEAR(read.laser_pose->y, -0.1, 1e-12);
  EXPECT_NEAR(read.laser_pose->yaw, 0.25, 1e-12);
}

TEST(Rosbag2, ABagFolderIsReadInTheOrderOfItsMetadata) {
  test::TempDir dir;
  const auto folder = dir.path() / "run";
  std::filesystem::create_directories(folder);
  ScanLog first = timedLog(), second = timedLog();
  for (LogEntry &entry : second.entries) entry.scan.stamp += 10.0;
  writeRosbag2((folder / "b_0.db3").string(), first);
  writeRosbag2((folder / "a_1.db3").string(), second);
  std::ofstream((folder / "metadata.yaml").string()) << "rosbag2_bagfile_information:\n"
                                                        "  version: 5\n"
                                                        "  storage_identifier: sqlite3\n"
                                                        "  relative_file_paths:\n"
                                                        "    - b_0.db3\n"
                                                        "    - a_1.db3\n";
  const ScanLog log = readLog(folder.string());
  ASSERT_EQ(log.entries.size(), 6u);
  EXPECT_EQ(log.report.reordered, 0u);
  EXPECT_NEAR(log.entries[5].scan.stamp, 11.0, 1e-9);
}

TEST(Rosbag2, AnMcapBagIsNamedAsSuch) {
  test::TempDir dir;
  const auto folder = dir.path() / "mcap_run";
  std::filesystem::create_directories(folder);
  std::ofstream((folder / "metadata.yaml").string()) << "rosbag2_bagfile_information:\n"
                                                        "  storage_identifier: mcap\n"
                                                        "  relative_file_paths: [mcap_run_0.mcap]\n";
  for (const std::string &path : {folder.string(), dir.write("run.mcap", "\x89MCAP0\r\n")}) {
    try {
      readLog(path);
      FAIL() << path;
    } catch (const ReadError &error) {
      const std::string what = error.what();
      EXPECT_NE(what.find(path), std::string::npos) << what;
      EXPECT_NE(what.find("ros2 bag convert"), std::string::npos) << what;
    }
  }
}

TEST(Rosbag2, ANonBagIsAnErrorNamingTheFile) {
  test::TempDir dir;
  for (const std::string &path : {dir.write("broken.db3", "SQLite format 3\0 truncated"), dir.file("empty.db3")}) {
    if (path.find("empty") != std::string::npos) writeDb3(path, {});
    try {
      const ScanLog log = readLog(path);
      FAIL() << path << ": " << log.entries.size() << " scans";
    } catch (const ReadError &error) {
      EXPECT_NE(std::string(error.what()).find(path), std::string::npos) << error.what();
    }
  }
}

TEST(Rosbag2, ANamedTopicTheBagDoesNotCarryIsAnError) {
  test::TempDir dir;
  const std::string path = dir.file("hand.db3");
  writeDb3(path, {{7, 12'250'000'000, handMadeScan()}});
  LogReadOptions options;
  options.scan_topic = "/scan";
  try {
    readLog(path, options);
    FAIL();
  } catch (const ReadError &error) {
    EXPECT_NE(std::string(error.what()).find("it has /front/scan"), std::string::npos) << error.what();
  }
  options.scan_topic = "/front/scan";
  EXPECT_EQ(readLog(path, options).entries.size(), 1u);
}

}  // namespace
}  // namespace contour_reg::io
