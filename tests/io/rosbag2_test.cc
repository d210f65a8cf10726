#include <lz4frame.h>
#include <sqlite3.h>
#include <zlib.h>
#include <zstd.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
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

// tf2_msgs/msg/TFMessage with one transform "odom" -> "base_link" at `stamp_s`: the wheel
// odometry as a robot's tf gives it, x `x`, y -2, yaw 90 deg ("odom" ends at 21, so the child's
// length is padded to 24; "base_link" ends at 38, the doubles from 40).
std::vector<std::uint8_t> handMadeOdometryTransform(double stamp_s, double x) {
  Bytes b;
  b.at<std::uint32_t>(0, 1).at<std::int32_t>(4, static_cast<std::int32_t>(stamp_s)).at<std::uint32_t>(8, 0);
  b.at<std::uint32_t>(12, 5).text(16, "odom");
  b.at<std::uint32_t>(24, 10).text(28, "base_link");
  b.at<double>(40, x).at<double>(48, -2.0).at<double>(56, 0.0);
  b.at<double>(64, 0.0).at<double>(72, 0.0).at<double>(80, std::sqrt(0.5)).at<double>(88, std::sqrt(0.5));
  return b.data();
}

// sensor_msgs/msg/MultiEchoLaserScan as handMadeScan() lays out its fields, then three beams of
// 2, 0 and 1 echoes (each a sequence of float32: 1.2 and 1.5 m, none, 3 m), no intensities.
std::vector<std::uint8_t> handMadeMultiEchoScan() {
  Bytes b;
  b.at<std::int32_t>(0, 12).at<std::uint32_t>(4, 250000000u).at<std::uint32_t>(8, 6).text(12, "laser");
  b.at<float>(20, -1.5f).at<float>(24, -0.5f).at<float>(28, 0.5f);  // angle_min, angle_max, angle_increment
  b.at<float>(32, 0.001f).at<float>(36, 0.1f);                      // time_increment, scan_time
  b.at<float>(40, 0.1f).at<float>(44, 20.0f);                       // range_min, range_max
  b.at<std::uint32_t>(48, 3);                                       // beams
  b.at<std::uint32_t>(52, 2).at<float>(56, 1.2f).at<float>(60, 1.5f);
  b.at<std::uint32_t>(64, 0);
  b.at<std::uint32_t>(68, 1).at<float>(72, 3.0f);
  b.at<std::uint32_t>(76, 0);  // no intensities
  return b.data();
}

struct Message {
  int topic;
  std::int64_t stamp_ns;
  std::vector<std::uint8_t> data;
};

// A .db3 file with rosbag2's sqlite3 schema, written with SQLite directly: the topics of the
// messages (numbered as below), then the messages.
void writeDb3(const std::string &path, const std::vector<Message> &messages) {
  const std::map<int, std::string> topics = {{7, "'/front/scan', 'sensor_msgs/msg/LaserScan'"},
                                             {8, "'/wheel/odom', 'nav_msgs/msg/Odometry'"},
                                             {9, "'/tf_static', 'tf2_msgs/msg/TFMessage'"},
                                             {10, "'/chatter', 'std_msgs/msg/String'"},
                                             {11, "'/tf', 'tf2_msgs/msg/TFMessage'"},
                                             {12, "'/horizontal_laser_2d', 'sensor_msgs/msg/MultiEchoLaserScan'"}};
  std::set<int> used;
  for (const Message &m : messages) used.insert(m.topic);
  std::string tables =
      "CREATE TABLE topics(id INTEGER PRIMARY KEY, name TEXT NOT NULL, type TEXT NOT NULL,"
      " serialization_format TEXT NOT NULL, offered_qos_profiles TEXT NOT NULL);"
      "CREATE TABLE messages(id INTEGER PRIMARY KEY, topic_id INTEGER NOT NULL,"
      " timestamp INTEGER NOT NULL, data BLOB NOT NULL);";
  for (const int id : used)
    tables += "INSERT INTO topics VALUES(" + std::to_string(id) + ", " + topics.at(id) + ", 'cdr', '');";
  sqlite3 *db = nullptr;
  ASSERT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
  ASSERT_EQ(sqlite3_exec(db, tables.c_str(), nullptr, nullptr, nullptr), SQLITE_OK);
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
  test::expectOdometryAQuarterOfTheWay(log);
  // The mounting: the scan's frame "laser" in the odometry's child frame "base_link".
  ASSERT_TRUE(log.laser_pose.has_value());
  EXPECT_NEAR(log.laser_pose->x, 0.2, 1e-12);
  EXPECT_NEAR(std::abs(log.laser_pose->yaw), M_PI, 1e-12);
}

// Many bags carry a robot's wheel odometry only as tf, the transform from "odom" to the robot's
// frame (REP 105), with no nav_msgs/Odometry topic: it is the log's odometry then.
TEST(Rosbag2, OdometryOnlyAsTransformsIsTheLogsOdometry) {
  test::TempDir dir;
  const std::string path = dir.file("tf.db3");
  writeDb3(path, {{9, 11'000'000'000, handMadeMounting()},
                  {11, 12'000'000'000, handMadeOdometryTransform(12.0, 1.5)},
                  {7, 12'250'000'000, handMadeScan()},
                  {11, 13'000'000'000, handMadeOdometryTransform(13.0, 2.5)}});
  const ScanLog log = readLog(path);
  EXPECT_TRUE(log.report.problems.empty()) << log.report.problems.front();
  test::expectOdometryAQuarterOfTheWay(log);
  ASSERT_TRUE(log.laser_pose.has_value());
  EXPECT_NEAR(log.laser_pose->x, 0.2, 1e-12);
  // An Odometry topic, where the bag has one, is the odometry.
  const std::string both = dir.file("both.db3");
  writeDb3(both, {{11, 12'000'000'000, handMadeOdometryTransform(12.0, 7.0)},
                  {8, 12'000'000'000, handMadeOdometry(12.0, 1.5)},
                  {7, 12'250'000'000, handMadeScan()},
                  {8, 13'000'000'000, handMadeOdometry(13.0, 2.5)},
                  {11, 13'000'000'000, handMadeOdometryTransform(13.0, 8.0)}});
  test::expectOdometryAQuarterOfTheWay(readLog(both));
}

// Some LIDARs' drivers publish every echo of a beam (sensor_msgs/msg/MultiEchoLaserScan, as
// Cartographer's public 2-D bags carry them): each beam's first echo is its range, a beam
// without one no return. A LaserScan topic, where the bag has one, is read first.
TEST(Rosbag2, AMultiEchoScanReadsAsItsFirstEchoes) {
  test::TempDir dir;
  const std::string path = dir.file("echoes.db3");
  writeDb3(path, {{12, 12'250'000'000, handMadeMultiEchoScan()}});
  const ScanLog log = readLog(path);
  EXPECT_TRUE(log.report.problems.empty()) << log.report.problems.front();
  ASSERT_EQ(log.entries.size(), 1u);
  const LaserScan &scan = log.entries[0].scan;
  EXPECT_DOUBLE_EQ(scan.stamp, 12.25);
  EXPECT_FLOAT_EQ(static_cast<float>(scan.angle_increment), 0.5f);
  ASSERT_EQ(scan.ranges.size(), 3u);
  EXPECT_FLOAT_EQ(scan.ranges[0], 1.2f);
  EXPECT_TRUE(std::isnan(scan.ranges[1]));
  EXPECT_FLOAT_EQ(scan.ranges[2], 3.0f);
  // Named, it is read beside a LaserScan topic; unnamed, the LaserScan topic is.
  const std::string both = dir.file("both.db3");
  writeDb3(both, {{12, 12'250'000'000, handMadeMultiEchoScan()}, {7, 12'300'000'000, handMadeScan()}});
  EXPECT_FLOAT_EQ(readLog(both).entries[0].scan.ranges[0], 1.0f);
  LogReadOptions options;
  options.scan_topic = "/horizontal_laser_2d";
  EXPECT_FLOAT_EQ(readLog(both, options).entries[0].scan.ranges[0], 1.2f);
  // Beams that declare more echoes than the message holds: the scan is named, not read.
  std::vector<std::uint8_t> corrupt = handMadeMultiEchoScan();
  corrupt[4 + 68] = 0xff;  // the third beam's echo count
  writeDb3(dir.file("corrupt.db3"), {{12, 12'250'000'000, corrupt}, {12, 12'500'000'000, handMadeMultiEchoScan()}});
  const ScanLog read = readLog(dir.file("corrupt.db3"));
  EXPECT_EQ(read.entries.size(), 1u);
  ASSERT_EQ(read.report.problems.size(), 1u);
  EXPECT_NE(read.report.problems[0].find("longer than the message"), std::string::npos) << read.report.problems[0];
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

// A bag folder's metadata.yaml: rosbag2_bagfile_information with `fields` (lines indented by two).
void writeMetadata(const std::filesystem::path &folder, const std::string &fields) {
  std::ofstream((folder / "metadata.yaml").string()) << "rosbag2_bagfile_information:\n" << fields;
}

TEST(Rosbag2, ABagFolderIsReadInTheOrderOfItsMetadata) {
  test::TempDir dir;
  const auto folder = dir.path() / "run";
  std::filesystem::create_directories(folder);
  ScanLog first = timedLog(), second = timedLog();
  for (LogEntry &entry : second.entries) entry.scan.stamp += 10.0;
  writeRosbag2((folder / "b_0.db3").string(), first);
  writeRosbag2((folder / "a_1.db3").string(), second);
  writeMetadata(folder,
                "  version: 5\n"
                "  storage_identifier: sqlite3\n"
                "  relative_file_paths:\n"
                "    - b_0.db3\n"
                "    - a_1.db3\n");
  const ScanLog log = readLog(folder.string());
  ASSERT_EQ(log.entries.size(), 6u);
  EXPECT_EQ(log.report.reordered, 0u);
  EXPECT_NEAR(log.entries[5].scan.stamp, 11.0, 1e-9);
}

// An MCAP file laid out by hand from the specification (mcap.dev/spec): little-endian
// records of an opcode, a uint64 length and their fields; strings with a uint32 length.
class McapFile {
 public:
  McapFile() { bytes_.assign(kMagic, kMagic + 8); }
  // A schema (type) and its channel (topic) under the same id.
  McapFile &channel(std::uint16_t id, const std::string &topic, const std::string &type) {
    record(bytes_, 0x03, u16(id) + str(type) + str("ros2msg") + u32(0));
    record(bytes_, 0x04, u16(id) + u16(id) + str(topic) + str("cdr") + u32(0));
    return *this;
  }
  // A message record of `channel` with `cdr`, at the top level or into a chunk's records.
  static std::string message(std::uint16_t channel, const std::vector<std::uint8_t> &cdr) {
    std::string out;
    record(out, 0x05, u16(channel) + u32(0) + u64(0) + u64(0) + std::string(cdr.begin(), cdr.end()));
    return out;
  }
  McapFile &top(const std::string &records) {
    bytes_ += records;
    return *this;
  }
  // A chunk of `records` as stored (`stored`: compressed with `compression`), with `crc`.
  McapFile &chunk(const std::string &records, const std::string &stored, const std::string &compression,
                  std::uint32_t crc) {
    record(bytes_, 0x06,
           u64(0) + u64(0) + u64(records.size()) + u32(crc) + str(compression) + u64(stored.size()) + stored);
    return *this;
  }
  std::string end() const {
    std::string out = bytes_;
    record(out, 0x0F, u32(0));
    record(out, 0x02, u64(0) + u64(0) + u32(0));
    return out + std::string(kMagic, kMagic + 8);
  }
  std::string cutShort() const { return bytes_.substr(0, bytes_.size() - 3); }

 private:
  static constexpr char kMagic[8] = {'\x89', 'M', 'C', 'A', 'P', '0', '\r', '\n'};
  template <typename T>
  static std::string le(T value) {
    std::string out;
    for (std::size_t k = 0; k < sizeof(T); ++k) out.push_back(static_cast<char>((value >> (8 * k)) & 0xff));
    return out;
  }
  static std::string u16(std::uint16_t v) { return le(v); }
  static std::string u32(std::uint32_t v) { return le(v); }
  static std::string u64(std::uint64_t v) { return le(v); }
  static std::string str(const std::string &text) { return u32(static_cast<std::uint32_t>(text.size())) + text; }
  static void record(std::string &out, std::uint8_t opcode, const std::string &fields) {
    out.push_back(static_cast<char>(opcode));
    out += u64(fields.size()) + fields;
  }
  std::string bytes_;
};

std::uint32_t crcOf(const std::string &bytes) {
  return static_cast<std::uint32_t>(
      crc32(0, reinterpret_cast<const Bytef *>(bytes.data()), static_cast<uInt>(bytes.size())));
}

TEST(Rosbag2, AnMcapFileReadsUncompressedAndLz4Chunks) {
  test::TempDir dir;
  const std::string records = McapFile::message(1, handMadeScan()) + McapFile::message(2, handMadeOdometry(12.0, 1.5)) +
                              McapFile::message(2, handMadeOdometry(13.0, 2.5));
  std::string lz4(LZ4F_compressFrameBound(records.size(), nullptr), '\0');
  lz4.resize(LZ4F_compressFrame(lz4.data(), lz4.size(), records.data(), records.size(), nullptr));
  for (const auto &[compression, stored] :
       {std::make_pair(std::string(), records), std::make_pair(std::string("lz4"), lz4)}) {
    McapFile file;
    file.channel(1, "/front/scan", "sensor_msgs/msg/LaserScan").channel(2, "/wheel/odom", "nav_msgs/msg/Odometry");
    file.chunk(records, stored, compression, crcOf(records));
    const ScanLog log = readLog(dir.write("hand" + compression + ".mcap", file.end()));
    EXPECT_TRUE(log.report.problems.empty()) << log.report.problems.front();
    ASSERT_EQ(log.entries.size(), 1u) << compression;
    EXPECT_DOUBLE_EQ(log.entries[0].scan.stamp, 12.25);
    EXPECT_FLOAT_EQ(log.entries[0].scan.ranges[2], 3.0f);
    ASSERT_TRUE(log.entries[0].odometry.has_value());
    EXPECT_NEAR(log.entries[0].odometry->x, 1.75, 1e-9);
  }
}

TEST(Rosbag2, AnMcapChunkThatDoesNotMatchItsCrcIsNamedAndTheRestRead) {
  test::TempDir dir;
  const std::string records = McapFile::message(1, handMadeScan());
  McapFile file;
  file.channel(1, "/scan", "sensor_msgs/msg/LaserScan");
  file.chunk(records, records, "", crcOf(records) ^ 1u).top(McapFile::message(1, handMadeScan()));
  const std::string path = dir.write("crc.mcap", file.end());
  const ScanLog log = readLog(path);
  EXPECT_EQ(log.entries.size(), 1u);
  ASSERT_EQ(log.report.problems.size(), 1u);
  EXPECT_NE(log.report.problems.front().find(path), std::string::npos) << log.report.problems.front();
  EXPECT_NE(log.report.problems.front().find("CRC"), std::string::npos) << log.report.problems.front();
}

TEST(Rosbag2, AnMcapFileCutShortIsAnErrorNamingTheFile) {
  test::TempDir dir;
  McapFile file;
  file.channel(1, "/scan", "sensor_msgs/msg/LaserScan").top(McapFile::message(1, handMadeScan()));
  for (const std::string &path : {dir.write("short.mcap", file.cutShort()), dir.write("magic.mcap", "\x89MCAP0\r")}) {
    try {
      readLog(path);
      FAIL() << path;
    } catch (const ReadError &error) {
      EXPECT_NE(std::string(error.what()).find(path), std::string::npos) << error.what();
    }
  }
}

TEST(Rosbag2, AWrittenMcapBagReadsBackAsTheSqliteOne) {
  test::TempDir dir;
  ScanLog written = timedLog();
  written.laser_pose = Pose2D{0.3, -0.1, 0.25};
  writeRosbag2(dir.file("timed.mcap"), written);
  const ScanLog read = readLog(dir.file("timed.mcap"));
  test::expectTimedLogReadBack(read, written);
  ASSERT_TRUE(read.laser_pose.has_value());
  EXPECT_NEAR(read.laser_pose->yaw, 0.25, 1e-12);
  // A bag folder whose metadata names its storage: the same.
  const auto folder = dir.path() / "run";
  std::filesystem::create_directories(folder);
  std::filesystem::copy_file(dir.file("timed.mcap"), folder / "run_0.mcap");
  writeMetadata(folder,
                "  storage_identifier: mcap\n"
                "  relative_file_paths: [run_0.mcap]\n");
  EXPECT_EQ(readLog(folder.string()).entries.size(), written.entries.size());
}

// The little-endian number of `size` bytes at `bytes`.
std::uint64_t littleEndian(const unsigned char *bytes, std::size_t size) {
  std::uint64_t value = 0;
  for (std::size_t k = 0; k < size; ++k) value |= std::uint64_t(bytes[k]) << (8 * k);
  return value;
}

// Little-endian fields of a file's bytes, each checked against the bytes' end.
class Fields {
 public:
  explicit Fields(std::string bytes) : bytes_(std::move(bytes)) {}
  std::uint64_t number(std::size_t at, std::size_t size) const {
    if (at + size > bytes_.size() || at + size < at) throw std::out_of_range("past the bytes' end");
    return littleEndian(reinterpret_cast<const unsigned char *>(bytes_.data()) + at, size);
  }
  // The string (uint32 length, then its bytes) at `at`; `at` moves past it.
  std::string text(std::size_t &at) const {
    const std::size_t size = number(at, 4);
    if (at + 4 + size > bytes_.size()) throw std::out_of_range("past the bytes' end");
    std::string value = bytes_.substr(at + 4, size);
    at += 4 + size;
    return value;
  }
  const std::string &bytes() const { return bytes_; }

 private:
  std::string bytes_;
};

// The schemas of an MCAP file written by writeRosbag2: type name -> definition text, from its
// top-level schema records (encoding ros2msg).
std::map<std::string, std::string> writtenSchemas(const std::string &path) {
  const Fields file(test::readBytes(path));
  std::map<std::string, std::string> schemas;
  for (std::size_t at = 8; at + 9 <= file.bytes().size();) {
    const auto opcode = file.number(at, 1);
    const std::size_t length = file.number(at + 1, 8), content = at + 9;
    if (opcode == 0x0F) break;  // the data end: the summary after it repeats the schemas
    if (opcode == 0x03) {
      std::size_t field = content + 2;
      const std::string name = file.text(field);
      EXPECT_EQ(file.text(field), "ros2msg") << name;
      schemas[name] = file.text(field);
    }
    at = content + length;
  }
  return schemas;
}

// What a viewer does with a schema: walks a CDR message by the fields of a ros2msg definition
// (its message, then "MSG: package/Name" sections after lines of '='), collecting each scalar,
// string and sequence length by its path ("pose.pose.position.x", "ranges.size").
class DefinitionWalk {
 public:
  DefinitionWalk(const std::string &definition, const std::vector<std::uint8_t> &cdr) : cdr_(cdr) {
    std::istringstream lines(definition);
    std::string line, section;
    while (std::getline(lines, line)) {
      if (line.find_first_not_of('=') == std::string::npos && line.size() >= 3) continue;
      if (line.rfind("MSG: ", 0) == 0) {
        section = normalized(line.substr(5));
        continue;
      }
      std::istringstream words(line.substr(0, line.find('#')));
      std::string type, name;
      if (words >> type >> name) types_[section].push_back({type, name});
    }
    walk("", "");
    EXPECT_EQ(4 + offset_, cdr_.size()) << "the definition does not end where the message does";
  }
  std::map<std::string, double> numbers;
  std::map<std::string, std::string> strings;

 private:
  static std::string normalized(std::string type) {
    const auto msg = type.find("/msg/");
    return msg == std::string::npos ? type : type.erase(msg, 4);
  }
  void align(std::size_t size) { offset_ = (offset_ + size - 1) / size * size; }
  std::uint64_t raw(std::size_t size) {
    align(size);
    if (4 + offset_ + size > cdr_.size()) throw std::out_of_range("past the message's end");
    const std::uint64_t value = littleEndian(cdr_.data() + 4 + offset_, size);
    offset_ += size;
    return value;
  }
  void one(const std::string &type, const std::string &path) {
    if (type == "string") {
      const std::size_t size = raw(4);
      if (4 + offset_ + size > cdr_.size()) throw std::out_of_range("past the message's end");
      strings[path] = std::string(cdr_.begin() + 4 + offset_, cdr_.begin() + 4 + offset_ + size - 1);
      offset_ += size;
    } else if (type == "float64") {
      const std::uint64_t bits = raw(8);
      double value;
      std::memcpy(&value, &bits, 8);
      numbers[path] = value;
    } else if (type == "float32") {
      const auto bits = static_cast<std::uint32_t>(raw(4));
      float value;
      std::memcpy(&value, &bits, 4);
      numbers[path] = value;
    } else if (type == "int32" || type == "uint32") {
      const auto bits = static_cast<std::uint32_t>(raw(4));
      numbers[path] = type == "int32" ? double(static_cast<std::int32_t>(bits)) : double(bits);
    } else {
      ASSERT_TRUE(types_.count(normalized(type))) << "no definition of " << type;
      walk(normalized(type), path + ".");
    }
  }
  void walk(const std::string &section, const std::string &prefix) {
    for (const auto &[type, name] : types_.at(section)) {
      const auto bracket = type.find('[');
      if (bracket == std::string::npos) {
        one(type, prefix + name);
        continue;
      }
      const std::string element = type.substr(0, bracket), bound = type.substr(bracket + 1, type.size() - bracket - 2);
      const std::size_t count = bound.empty() ? raw(4) : std::stoul(bound);
      numbers[prefix + name + ".size"] = double(count);
      for (std::size_t k = 0; k < count; ++k) one(element, prefix + name + "." + std::to_string(k));
    }
  }
  const std::vector<std::uint8_t> &cdr_;
  std::map<std::string, std::vector<std::pair<std::string, std::string>>> types_;
  std::size_t offset_ = 0;
};

// A viewer such as Foxglove decodes a topic by its schema's definition: each type written
// carries one, and it walks the messages laid out by hand above field by field to their end.
TEST(Rosbag2, AWrittenMcapBagDefinesItsMessages) {
  test::TempDir dir;
  ScanLog written = timedLog();
  written.laser_pose = Pose2D{0.3, -0.1, 0.25};
  writeRosbag2(dir.file("timed.mcap"), written);
  const std::map<std::string, std::string> schemas = writtenSchemas(dir.file("timed.mcap"));
  ASSERT_EQ(schemas.size(), 3u);
  for (const auto &[type, definition] : schemas) EXPECT_FALSE(definition.empty()) << type;

  const DefinitionWalk scan(schemas.at("sensor_msgs/msg/LaserScan"), handMadeScan());
  EXPECT_EQ(scan.strings.at("header.frame_id"), "laser");
  EXPECT_EQ(scan.numbers.at("header.stamp.nanosec"), 250000000.0);
  EXPECT_FLOAT_EQ(float(scan.numbers.at("range_max")), 20.0f);
  EXPECT_EQ(scan.numbers.at("ranges.size"), 3.0);
  EXPECT_FLOAT_EQ(float(scan.numbers.at("ranges.1")), 25.0f);
  EXPECT_EQ(scan.numbers.at("intensities.size"), 0.0);

  const DefinitionWalk odometry(schemas.at("nav_msgs/msg/Odometry"), handMadeOdometry(12.0, 1.5));
  EXPECT_EQ(odometry.strings.at("child_frame_id"), "base_link");
  EXPECT_EQ(odometry.numbers.at("pose.pose.position.x"), 1.5);
  EXPECT_EQ(odometry.numbers.at("pose.pose.orientation.w"), std::sqrt(0.5));
  EXPECT_EQ(odometry.numbers.at("twist.covariance.size"), 36.0);

  const DefinitionWalk transforms(schemas.at("tf2_msgs/msg/TFMessage"), handMadeMounting());
  EXPECT_EQ(transforms.numbers.at("transforms.size"), 1.0);
  EXPECT_EQ(transforms.strings.at("transforms.0.header.frame_id"), "base_link");
  EXPECT_EQ(transforms.strings.at("transforms.0.child_frame_id"), "laser");
  EXPECT_EQ(transforms.numbers.at("transforms.0.transform.translation.x"), 0.2);
  EXPECT_EQ(transforms.numbers.at("transforms.0.transform.rotation.z"), 1.0);
}

// A log long enough for more than one chunk: `scans` scans of 200 beams at 10 Hz, each with odometry.
ScanLog longLog(int scans) {
  ScanLog log;
  for (int k = 0; k < scans; ++k) {
    LogEntry entry;
    entry.scan.stamp = 0.1 * k;
    entry.scan.angle_min = -1.5;
    entry.scan.angle_increment = 0.015;
    entry.scan.range_max = 30.0;
    entry.scan.ranges.assign(200, 2.0f + 0.001f * static_cast<float>(k));
    entry.odometry = Pose2D{0.01 * k, 0.0, 0.0};
    log.entries.push_back(entry);
  }
  log.laser_pose = Pose2D{0.2, 0.0, 0.0};
  return log;
}

// A reader that seeks, as Foxglove's indexed reader and `mcap info` do, starts at the footer:
// the summary section it points to gives the statistics and, for each chunk, where it lies and
// where the index of each channel's messages in it lies (mcap.dev/spec). Every pointer of the
// written summary is followed to the record it names.
TEST(Rosbag2, AWrittenMcapBagHasASummaryThatIndexesEveryMessage) {
  test::TempDir dir;
  const ScanLog written = longLog(3000);
  writeRosbag2(dir.file("long.mcap"), written);
  const Fields file(test::readBytes(dir.file("long.mcap")));
  const std::string &bytes = file.bytes();
  const std::size_t footer = bytes.size() - 8 - 29;
  ASSERT_EQ(file.number(footer, 1), 0x02u);
  const std::size_t summary = file.number(footer + 9, 8), offsets = file.number(footer + 17, 8);
  ASSERT_GT(summary, 0u) << "no summary section";
  ASSERT_LT(summary, offsets);
  ASSERT_LT(offsets, footer);
  EXPECT_EQ(file.number(footer + 25, 4), crcOf(bytes.substr(summary, footer + 25 - summary)));

  // The summary's records by opcode, each group's span, and the summary offsets that name them.
  std::map<int, std::vector<std::size_t>> records;  // opcode -> each record's content start
  std::map<int, std::pair<std::size_t, std::size_t>> groups;
  for (std::size_t at = summary; at < offsets;) {
    const int opcode = static_cast<int>(file.number(at, 1));
    const std::size_t end = at + 9 + file.number(at + 1, 8);
    records[opcode].push_back(at + 9);
    if (!groups.count(opcode)) groups[opcode].first = at;
    EXPECT_EQ(groups[opcode].first + groups[opcode].second, at) << "opcode " << opcode << " is not one group";
    groups[opcode].second = end - groups[opcode].first;
    at = end;
  }
  std::map<int, std::pair<std::size_t, std::size_t>> named;
  for (std::size_t at = offsets; at < footer; at += 9 + file.number(at + 1, 8)) {
    ASSERT_EQ(file.number(at, 1), 0x0Eu);
    named[static_cast<int>(file.number(at + 9, 1))] = {file.number(at + 10, 8), file.number(at + 18, 8)};
  }
  EXPECT_EQ(named, groups);
  ASSERT_EQ(records[0x03].size(), 3u);  // schemas
  ASSERT_EQ(records[0x04].size(), 3u);  // channels
  ASSERT_EQ(records[0x0B].size(), 1u);  // statistics
  ASSERT_GE(records[0x08].size(), 2u);  // chunk indexes

  // Each chunk index leads to its chunk, and through its message indexes to every message in it.
  std::map<std::uint64_t, std::uint64_t> indexed;  // channel -> messages
  std::uint64_t first_time = ~0ull, last_time = 0;
  for (const std::size_t index : records[0x08]) {
    const std::uint64_t start_time = file.number(index, 8), end_time = file.number(index + 8, 8);
    const std::size_t chunk = file.number(index + 16, 8), chunk_length = file.number(index + 24, 8);
    ASSERT_EQ(file.number(chunk, 1), 0x06u);
    EXPECT_EQ(chunk_length, 9 + file.number(chunk + 1, 8));
    std::size_t field = chunk + 9 + 16;
    const std::size_t uncompressed = file.number(field, 8);
    field += 12;
    EXPECT_EQ(file.text(field), "zstd");
    const std::size_t stored = file.number(field, 8);
    std::string records_of_chunk(uncompressed, '\0');
    ASSERT_EQ(ZSTD_decompress(records_of_chunk.data(), uncompressed, bytes.data() + field + 8, stored), uncompressed);
    const Fields chunk_records(records_of_chunk);

    std::size_t at = index + 32;
    const std::size_t map_end = at + 4 + file.number(at, 4);
    std::size_t next_index = chunk + chunk_length, index_bytes = 0;
    for (at += 4; at < map_end; at += 10) {
      const std::uint64_t channel = file.number(at, 2);
      const std::size_t message_index = file.number(at + 2, 8);
      EXPECT_EQ(message_index, next_index) << "the message indexes follow their chunk";
      ASSERT_EQ(file.number(message_index, 1), 0x07u);
      const std::size_t length = file.number(message_index + 1, 8);
      next_index = message_index + 9 + length;
      index_bytes += 9 + length;
      EXPECT_EQ(file.number(message_index + 9, 2), channel);
      const std::size_t entries = file.number(message_index + 11, 4) / 16;
      for (std::size_t k = 0; k < entries; ++k) {
        const std::uint64_t time = file.number(message_index + 15 + 16 * k, 8);
        const std::size_t offset = file.number(message_index + 23 + 16 * k, 8);
        ASSERT_EQ(chunk_records.number(offset, 1), 0x05u);
        EXPECT_EQ(chunk_records.number(offset + 9, 2), channel);
        EXPECT_EQ(chunk_records.number(offset + 15, 8), time);
        EXPECT_GE(time, start_time);
        EXPECT_LE(time, end_time);
        first_time = std::min(first_time, time);
        last_time = std::max(last_time, time);
      }
      indexed[channel] += entries;
    }
    EXPECT_EQ(file.number(at, 8), index_bytes) << "message_index_length";
    std::size_t compression = at + 8;
    EXPECT_EQ(file.text(compression), "zstd");
    EXPECT_EQ(file.number(compression, 8), stored);
    EXPECT_EQ(file.number(compression + 8, 8), uncompressed);
  }
  // The scans, the odometry samples and the one mounting transform, all indexed.
  EXPECT_EQ(indexed, (std::map<std::uint64_t, std::uint64_t>{{1, 3000}, {2, 3000}, {3, 1}}));
  EXPECT_EQ(first_time, 0u);
  EXPECT_EQ(last_time, 299'900'000'000u);

  const std::size_t statistics = records[0x0B].front();
  EXPECT_EQ(file.number(statistics, 8), 6001u);                      // messages
  EXPECT_EQ(file.number(statistics + 8, 2), 3u);                     // schemas
  EXPECT_EQ(file.number(statistics + 10, 4), 3u);                    // channels
  EXPECT_EQ(file.number(statistics + 22, 4), records[0x08].size());  // chunks
  EXPECT_EQ(file.number(statistics + 26, 8), first_time);
  EXPECT_EQ(file.number(statistics + 34, 8), last_time);
  std::map<std::uint64_t, std::uint64_t> counted;
  const std::size_t counts_end = statistics + 46 + file.number(statistics + 42, 4);
  for (std::size_t at = statistics + 46; at < counts_end; at += 10)
    counted[file.number(at, 2)] = file.number(at + 2, 8);
  EXPECT_EQ(counted, indexed);
  // The bag still reads back whole.
  EXPECT_EQ(readLog(dir.file("long.mcap")).entries.size(), 3000u);
}

// rosbag2's compression (`ros2 bag record --compression-format zstd`): in file mode each
// storage file is compressed whole into `name.zstd`, in message mode each message's bytes are;
// both are zstd frames.
std::string zstdOf(const std::string &bytes) {
  std::string out(ZSTD_compressBound(bytes.size()), '\0');
  out.resize(ZSTD_compress(out.data(), out.size(), bytes.data(), bytes.size(), 1));
  return out;
}
std::vector<std::uint8_t> zstdOf(const std::vector<std::uint8_t> &bytes) {
  const std::string out = zstdOf(std::string(bytes.begin(), bytes.end()));
  return {out.begin(), out.end()};
}

TEST(Rosbag2, ABagCompressedFileByFileReadsAsTheBagItHolds) {
  const std::string zeros = zstdOf(std::string(70u << 20, '\0'));
  for (const std::string storage : {"db3", "mcap"}) {
    SCOPED_TRACE(storage);
    test::TempDir dir;
    const ScanLog written = timedLog();
    writeRosbag2(dir.file("run_0." + storage), written);
    const auto folder = dir.path() / "run";
    std::filesystem::create_directories(folder);
    const std::string compressed = zstdOf(test::readBytes(dir.file("run_0." + storage)));
    std::ofstream((folder / ("run_0." + storage + ".zstd")).string(), std::ios::binary) << compressed;
    writeMetadata(folder, "  storage_identifier: " + std::string(storage == "db3" ? "sqlite3" : "mcap") +
                              "\n  relative_file_paths: [run_0." + storage +
                              ".zstd]\n  compression_format: zstd\n  compression_mode: FILE\n");
    test::expectTimedLogReadBack(readLog(folder.string()), written);
    // The compressed file alone reads the same.
    test::expectTimedLogReadBack(readLog((folder / ("run_0." + storage + ".zstd")).string()), written);
    // One cut short is an error naming it, and so is one that decompresses to far more than a
    // bag's messages could (70 MB of zeros in 2 kB), before it is written out.
    const std::string cut = dir.write("cut." + storage + ".zstd", compressed.substr(0, compressed.size() / 2));
    const std::string bomb = dir.write("bomb." + storage + ".zstd", zeros);
    for (const auto &[path, why] : {std::pair(cut, "cut short"), std::pair(bomb, "1000 times its size")}) {
      try {
        readLog(path);
        FAIL() << path << " read";
      } catch (const ReadError &error) {
        EXPECT_NE(std::string(error.what()).find(path), std::string::npos) << error.what();
        EXPECT_NE(std::string(error.what()).find(why), std::string::npos) << error.what();
      }
    }
  }
}

TEST(Rosbag2, ABagCompressedMessageByMessageReadsItsMessages) {
  test::TempDir dir;
  const std::string path = dir.file("messages.db3");
  std::vector<std::uint8_t> broken = zstdOf(handMadeScan());
  broken.resize(broken.size() / 2);
  writeDb3(path, {{9, 11'000'000'000, zstdOf(handMadeMounting())},
                  {8, 12'000'000'000, zstdOf(handMadeOdometry(12.0, 1.5))},
                  {7, 12'250'000'000, zstdOf(handMadeScan())},
                  {7, 12'500'000'000, broken},
                  {8, 13'000'000'000, zstdOf(handMadeOdometry(13.0, 2.5))}});
  const ScanLog log = readLog(path);
  ASSERT_EQ(log.entries.size(), 1u);
  const LaserScan &scan = log.entries[0].scan;
  EXPECT_DOUBLE_EQ(scan.stamp, 12.25);
  ASSERT_EQ(scan.ranges.size(), 3u);
  EXPECT_FLOAT_EQ(scan.ranges[2], 3.0f);
  test::expectOdometryAQuarterOfTheWay(log);
  ASSERT_TRUE(log.laser_pose.has_value());
  EXPECT_NEAR(log.laser_pose->x, 0.2, 1e-12);
  ASSERT_EQ(log.report.problems.size(), 1u);
  EXPECT_NE(log.report.problems[0].find("cannot decompress"), std::string::npos) << log.report.problems[0];
}

TEST(Rosbag2, ABagOfAnotherCompressionIsAnErrorNamingIt) {
  test::TempDir dir;
  const auto folder = dir.path() / "run";
  std::filesystem::create_directories(folder);
  writeRosbag2((folder / "run_0.db3").string(), timedLog());
  writeMetadata(folder,
                "  storage_identifier: sqlite3\n"
                "  relative_file_paths: [run_0.db3]\n"
                "  compression_format: brotli\n"
                "  compression_mode: MESSAGE\n");
  try {
    readLog(folder.string());
    FAIL();
  } catch (const ReadError &error) {
    EXPECT_NE(std::string(error.what()).find("brotli"), std::string::npos) << error.what();
  }
  // An uncompressed bag's metadata names no compression.
  writeMetadata(folder,
                "  storage_identifier: sqlite3\n"
                "  relative_file_paths: [run_0.db3]\n"
                "  compression_format: \"\"\n"
                "  compression_mode: \"\"\n");
  EXPECT_EQ(readLog(folder.string()).entries.size(), 3u);
}

// writeLog goes by the name: one that asks for a compressed storage file is refused rather
// than written as a CARMEN log under that name.
TEST(Rosbag2, ACompressedStorageFileIsNotWrittenAsAnotherFormat) {
  test::TempDir dir;
  for (const std::string name : {"run.mcap.zstd", "run.db3.zstd"}) {
    try {
      writeLog(dir.file(name), timedLog());
      FAIL() << name << " written";
    } catch (const ReadError &error) {
      EXPECT_NE(std::string(error.what()).find(name), std::string::npos) << error.what();
    }
    EXPECT_FALSE(std::filesystem::exists(dir.file(name)));
  }
}

TEST(Rosbag2, AnotherStorageIsAnErrorNamingIt) {
  test::TempDir dir;
  const auto folder = dir.path() / "run";
  std::filesystem::create_directories(folder);
  writeMetadata(folder,
                "  storage_identifier: zarr\n"
                "  relative_file_paths: [run_0.zarr]\n");
  try {
    readLog(folder.string());
    FAIL();
  } catch (const ReadError &error) {
    EXPECT_NE(std::string(error.what()).find("zarr storage"), std::string::npos) << error.what();
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
