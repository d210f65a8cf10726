#include <cmath>
#include <fstream>
#include <iterator>

#include <gtest/gtest.h>

#include "contour_reg/io/carmen.h"
#include "contour_reg/io/read_log.h"
#include "contour_reg/io/rosbag.h"
#include "temp_dir.h"
#include "timed_log.h"

#ifdef CONTOUR_REG_HAVE_ROSBAG
#include <rosbag/bag.h>
#include <sensor_msgs/LaserScan.h>
#include <sensor_msgs/MultiEchoLaserScan.h>
#include <tf2_msgs/TFMessage.h>
#endif

namespace contour_reg::io {
namespace {

using test::timedLog;

TEST(Rosbag, ANonBagIsAnErrorNamingTheFile) {
  test::TempDir dir;
  const auto path = dir.write("broken.bag", "#ROSBAG V2.0\n\x01\x02\x03 truncated");
  try {
    readLog(path);
    FAIL();
  } catch (const ReadError &error) {
    EXPECT_NE(std::string(error.what()).find(path), std::string::npos) << error.what();
  }
}

TEST(Rosbag, AWrittenBagReadsBackWithBeamTimingAndOdometry) {
  if (!rosbagSupported()) GTEST_SKIP() << "built without ROS bag support";
  test::TempDir dir;
  const std::string path = (dir.path() / "timed.bag").string();
  const ScanLog written = timedLog();
  writeRosbag(path, written);
  const ScanLog read = readLog(path);
  test::expectTimedLogReadBack(read, written);
  // A scan period given for untimed scans leaves the bag's own timing alone.
  LogReadOptions options;
  options.scan_period = 0.1;
  const ScanLog with_period = readLog(path, options);
  EXPECT_FLOAT_EQ(static_cast<float>(with_period.entries[0].scan.time_increment), 0.01f);
  EXPECT_NEAR(with_period.entries[1].scan.time_increment, 0.1 * 0.5 / (2 * M_PI), 1e-9);
}

#ifdef CONTOUR_REG_HAVE_ROSBAG
// A transform `parent` -> `child` at `stamp` s, x `x`, y -2, yaw 90 deg.
tf2_msgs::TFMessage transformAt(double stamp, const std::string &parent, const std::string &child, double x) {
  geometry_msgs::TransformStamped t;
  t.header.stamp = ros::Time(stamp);
  t.header.frame_id = parent;
  t.child_frame_id = child;
  t.transform.translation.x = x;
  t.transform.translation.y = -2.0;
  t.transform.rotation.z = t.transform.rotation.w = std::sqrt(0.5);
  tf2_msgs::TFMessage message;
  message.transforms.push_back(t);
  return message;
}

// A scan message (sensor_msgs/LaserScan or MultiEchoLaserScan) at 12.25 s in frame "laser":
// three beams from -1.5 rad, 0.5 rad apart, range_max 20 m; its ranges left to fill.
template <typename Message>
Message scanMessage() {
  Message message;
  message.header.stamp = ros::Time(12.25);
  message.header.frame_id = "laser";
  message.angle_min = -1.5f;
  message.angle_increment = 0.5f;
  message.angle_max = -0.5f;
  message.range_max = 20.0f;
  return message;
}

// Many bags carry a robot's wheel odometry only as tf, the transform from "odom" to the robot's
// frame (REP 105; here base_footprint, the laser on it through base_link), with no
// nav_msgs/Odometry topic: it is the log's odometry then.
TEST(Rosbag, OdometryOnlyAsTransformsIsTheLogsOdometry) {
  test::TempDir dir;
  const std::string path = dir.file("tf.bag");
  {
    rosbag::Bag bag(path, rosbag::bagmode::Write);
    bag.write("/tf_static", ros::Time(11.0), transformAt(11.0, "base_footprint", "base_link", 0.0));
    bag.write("/tf_static", ros::Time(11.0), transformAt(11.0, "base_link", "laser", 0.1));
    bag.write("/tf", ros::Time(12.0), transformAt(12.0, "odom", "base_footprint", 1.5));
    auto scan = scanMessage<sensor_msgs::LaserScan>();
    scan.ranges = {1.0f, 2.0f, 3.0f};
    bag.write("/scan", ros::Time(12.25), scan);
    bag.write("/tf", ros::Time(13.0), transformAt(13.0, "odom", "base_footprint", 2.5));
  }
  const ScanLog log = readLog(path);
  EXPECT_TRUE(log.report.problems.empty()) << log.report.problems.front();
  test::expectOdometryAQuarterOfTheWay(log);
  // The laser on base_footprint: base_link's pose composed with the laser's on it.
  ASSERT_TRUE(log.laser_pose.has_value());
  EXPECT_NEAR(log.laser_pose->x, 2.0, 1e-9);
  EXPECT_NEAR(log.laser_pose->y, -2.0 + 0.1, 1e-9);
  EXPECT_NEAR(std::abs(log.laser_pose->yaw), M_PI, 1e-9);
}

// Some LIDARs' drivers publish every echo of a beam (sensor_msgs/MultiEchoLaserScan, as
// Cartographer's public 2-D bags carry them): each beam's first echo is its range, a beam
// without one no return. A LaserScan topic, where the bag has one, is read first.
TEST(Rosbag, AMultiEchoScanReadsAsItsFirstEchoes) {
  test::TempDir dir;
  auto echoes = scanMessage<sensor_msgs::MultiEchoLaserScan>();
  echoes.ranges.resize(3);
  echoes.ranges[0].echoes = {1.2f, 1.5f};
  echoes.ranges[2].echoes = {3.0f};
  auto single = scanMessage<sensor_msgs::LaserScan>();
  single.ranges = {1.0f, 2.0f, 3.0f};
  const std::string path = dir.file("echoes.bag"), both = dir.file("both.bag");
  {
    rosbag::Bag bag(path, rosbag::bagmode::Write);
    bag.write("/horizontal_laser_2d", ros::Time(12.25), echoes);
    rosbag::Bag with_single(both, rosbag::bagmode::Write);
    with_single.write("/horizontal_laser_2d", ros::Time(12.25), echoes);
    with_single.write("/scan", ros::Time(12.25), single);
  }
  const ScanLog log = readLog(path);
  EXPECT_TRUE(log.report.problems.empty()) << log.report.problems.front();
  ASSERT_EQ(log.entries.size(), 1u);
  const LaserScan &scan = log.entries[0].scan;
  EXPECT_DOUBLE_EQ(scan.stamp, 12.25);
  ASSERT_EQ(scan.ranges.size(), 3u);
  EXPECT_FLOAT_EQ(scan.ranges[0], 1.2f);
  EXPECT_TRUE(std::isnan(scan.ranges[1]));
  EXPECT_FLOAT_EQ(scan.ranges[2], 3.0f);
  // Named, it is read beside a LaserScan topic; unnamed, the LaserScan topic is.
  EXPECT_FLOAT_EQ(readLog(both).entries[0].scan.ranges[0], 1.0f);
  LogReadOptions options;
  options.scan_topic = "/horizontal_laser_2d";
  EXPECT_FLOAT_EQ(readLog(both, options).entries[0].scan.ranges[0], 1.2f);
  options.scan_topic = "/front";
  try {
    readLog(both, options);
    FAIL();
  } catch (const ReadError &error) {
    EXPECT_NE(std::string(error.what()).find("it has /scan, /horizontal_laser_2d"), std::string::npos) << error.what();
  }
}
#endif

// timedLog() written as a bag at `path`, then `replacement` written over its bytes `offset`
// past the first (or, with `last`, the last) place where `pattern` occurs. False when the
// pattern does not occur.
bool writeCorruptBag(const std::string &path, const std::string &pattern, std::size_t offset,
                     const std::string &replacement, bool last = false) {
  writeRosbag(path, timedLog());
  std::string bytes = test::readBytes(path);
  const std::size_t at = last ? bytes.rfind(pattern) : bytes.find(pattern);
  if (at == std::string::npos) return false;
  bytes.replace(at + offset, replacement.size(), replacement);
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
  return true;
}

// rosbag_storage trusts the lengths in a bag's records: a message record whose header field
// claims more bytes than the chunk holds made it read out of bounds. Such a message is not
// read, and named with the chunk; the messages before it in the chunk are.
TEST(Rosbag, AMessageWhoseRecordIsCorruptIsSkippedAndNamed) {
  if (!rosbagSupported()) GTEST_SKIP() << "built without ROS bag support";
  test::TempDir dir;
  const std::string path = (dir.path() / "corrupt.bag").string();
  writeRosbag(path, timedLog());
  const ScanLog intact = readLog(path);
  // Each message record's header has the field "op" of the message kind, 4 bytes long.
  ASSERT_TRUE(writeCorruptBag(path, std::string("\x04\0\0\0op=\x02", 8), 0, "\xff\xff\xff\x7f", true));
  const ScanLog read = readLog(path);
  EXPECT_EQ(read.entries.size() + read.wheel_odometry.size() + 1, intact.entries.size() + intact.wheel_odometry.size());
  ASSERT_EQ(read.report.problems.size(), 1u);
  EXPECT_NE(read.report.problems.front().find("not read"), std::string::npos) << read.report.problems.front();
  EXPECT_NE(read.report.problems.front().find("is corrupt"), std::string::npos) << read.report.problems.front();
}

// A chunk that does not decompress (here one whose stated size is smaller than its data) was
// decompressed once more for every message in it, which takes minutes on a real bag. Its
// messages are not read, and named with the chunk.
TEST(Rosbag, AChunkThatDoesNotDecompressIsNamed) {
  if (!rosbagSupported()) GTEST_SKIP() << "built without ROS bag support";
  test::TempDir dir;
  const std::string path = (dir.path() / "corrupt.bag").string();
  // The chunk record's header has the field "size", the chunk's bytes decompressed.
  const std::string size_field("\x09\0\0\0size=", 9);
  ASSERT_TRUE(writeCorruptBag(path, size_field, size_field.size(), std::string("\x10\0\0\0", 4)));
  try {
    readLog(path);
    FAIL() << "no scan can be read";
  } catch (const ReadError &error) {
    EXPECT_NE(std::string(error.what()).find("a chunk that does not decompress"), std::string::npos) << error.what();
  }
}

// ROS's deserialization sizes an array from the length a message declares before it checks
// the message holds it: a corrupt length of the ranges asked for gigabytes. The scan is not
// read, and named.
TEST(Rosbag, AScanThatDeclaresMoreRangesThanItHoldsIsSkippedAndNamed) {
  if (!rosbagSupported()) GTEST_SKIP() << "built without ROS bag support";
  test::TempDir dir;
  const std::string path = (dir.path() / "corrupt.bag").string();
  // The first scan's ranges: their count, 4, then 1 and 2 as float32; 64 M ranges are 256 MB.
  ASSERT_TRUE(
      writeCorruptBag(path, std::string("\x04\0\0\0\0\0\x80\x3f\0\0\0\x40", 12), 0, std::string("\0\0\0\x04", 4)));
  const ScanLog read = readLog(path);
  EXPECT_EQ(read.entries.size(), timedLog().entries.size() - 1);
  ASSERT_EQ(read.report.problems.size(), 1u);
  EXPECT_NE(read.report.problems.front().find("an array longer than the message"), std::string::npos)
      << read.report.problems.front();
}

// The wheel odometry logged between the scans (ten samples a scan here) is written to /odom
// and read back whole, as the log's wheel_odometry.
TEST(Rosbag, WheelOdometryBetweenTheScansReadsBack) {
  if (!rosbagSupported()) GTEST_SKIP() << "built without ROS bag support";
  test::TempDir dir;
  const std::string path = (dir.path() / "odometry.bag").string();
  ScanLog written = timedLog();
  for (int i = 0; i <= 10; ++i) written.wheel_odometry.push_back({0.1 * i, Pose2D{0.06 * i, -0.02 * i, 0.04 * i}});
  writeRosbag(path, written);
  const ScanLog read = readLog(path);
  ASSERT_EQ(read.wheel_odometry.size(), written.wheel_odometry.size());
  for (std::size_t i = 0; i < read.wheel_odometry.size(); ++i) {
    EXPECT_NEAR(read.wheel_odometry[i].stamp, written.wheel_odometry[i].stamp, 1e-9);
    EXPECT_NEAR(read.wheel_odometry[i].pose.x, written.wheel_odometry[i].pose.x, 1e-9);
    EXPECT_NEAR(read.wheel_odometry[i].pose.yaw, written.wheel_odometry[i].pose.yaw, 1e-9);
  }
  // Each scan's odometry comes from the samples: at 0.5 s the sixth.
  ASSERT_TRUE(read.entries[1].odometry.has_value());
  EXPECT_NEAR(read.entries[1].odometry->x, 0.3, 1e-9);

  // Read without its wheel odometry (laser-only studies): the scans alone, their timing kept.
  LogReadOptions scans_only;
  scans_only.wheel_odometry = false;
  const ScanLog without = readLog(path, scans_only);
  ASSERT_EQ(without.entries.size(), read.entries.size());
  EXPECT_TRUE(without.wheel_odometry.empty());
  for (const LogEntry &entry : without.entries) EXPECT_FALSE(entry.odometry.has_value());
  EXPECT_EQ(without.entries[1].scan.time_increment, read.entries[1].scan.time_increment);
}

// A topic named for the scans or the odometry that the bag does not carry is an error naming
// the file, the topic and the topics of that type it does carry: a mistyped odometry topic must
// not read as a log without wheel odometry.
TEST(Rosbag, ANamedTopicTheBagDoesNotCarryIsAnError) {
  if (!rosbagSupported()) GTEST_SKIP() << "built without ROS bag support";
  test::TempDir dir;
  const std::string path = (dir.path() / "topics.bag").string();
  writeRosbag(path, timedLog());
  for (const bool odometry : {true, false}) {
    RosbagOptions options;
    (odometry ? options.odometry_topic : options.scan_topic) = "/wheels";
    try {
      readRosbag(path, options);
      FAIL() << (odometry ? "odometry" : "scan") << " topic /wheels accepted";
    } catch (const ReadError &error) {
      const std::string what = error.what();
      EXPECT_NE(what.find(path), std::string::npos) << what;
      EXPECT_NE(what.find("/wheels"), std::string::npos) << what;
      EXPECT_NE(what.find(odometry ? "/odom" : "/scan"), std::string::npos) << what;
    }
  }
}

// The laser's mounting is the static transform from the odometry's child frame (base_link) to
// the scan's frame; a bag without one has none.
TEST(Rosbag, TheMountingComesFromTheStaticTransforms) {
  if (!rosbagSupported()) GTEST_SKIP() << "built without ROS bag support";
  test::TempDir dir;
  ScanLog log = timedLog();
  writeRosbag(dir.file("plain.bag"), log);
  EXPECT_FALSE(readLog(dir.file("plain.bag")).laser_pose.has_value());
  log.laser_pose = Pose2D{0.3, -0.1, 0.25};
  writeRosbag(dir.file("mounted.bag"), log);
  const ScanLog read = readLog(dir.file("mounted.bag"));
  ASSERT_TRUE(read.laser_pose.has_value());
  EXPECT_NEAR(read.laser_pose->x, 0.3, 1e-9);
  EXPECT_NEAR(read.laser_pose->y, -0.1, 1e-9);
  EXPECT_NEAR(read.laser_pose->yaw, 0.25, 1e-9);
  EXPECT_NEAR(read.entries[2].odometry->x, 0.6, 1e-9);  // the robot's odometry is untouched
}

TEST(Rosbag, BeamTimingThatCannotBeUsedIsReportedAndDropped) {
  if (!rosbagSupported()) GTEST_SKIP() << "built without ROS bag support";
  test::TempDir dir;
  const std::string path = (dir.path() / "reversed.bag").string();
  ScanLog log = timedLog();
  log.entries[2].scan.time_increment = -0.01;
  writeRosbag(path, log);
  const ScanLog read = readLog(path);
  ASSERT_EQ(read.entries.size(), 3u);
  EXPECT_EQ(read.entries[2].scan.time_increment, 0.0);
  ASSERT_EQ(read.report.problems.size(), 1u);
  EXPECT_NE(read.report.problems[0].find("time_increment"), std::string::npos) << read.report.problems[0];
  EXPECT_NE(read.report.problems[0].find(path), std::string::npos) << read.report.problems[0];
}

// A bag's times start at its epoch: a scan stamped before it is an error, not a moved stamp.
TEST(Rosbag, ANegativeStampCannotBeWritten) {
  if (!rosbagSupported()) GTEST_SKIP() << "built without ROS bag support";
  test::TempDir dir;
  const std::string path = (dir.path() / "early.bag").string();
  ScanLog log = timedLog();
  log.entries[1].scan.stamp = -0.5;
  try {
    writeRosbag(path, log);
    FAIL() << "a negative stamp was written";
  } catch (const ReadError &error) {
    EXPECT_NE(std::string(error.what()).find(path), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("stamp"), std::string::npos) << error.what();
  }
}

TEST(Rosbag, IntelBagAgreesWithIntelLog) {
  if (!rosbagSupported()) GTEST_SKIP() << "built without ROS bag support";
  const std::string bag = test::sharedDataset("intel/intel.orig.bag"), clf = test::sharedDataset("intel/intel.clf");
  if (bag.empty() || clf.empty()) GTEST_SKIP() << "../shared/datasets/intel is absent";
  const ScanLog from_bag = readLog(bag), from_clf = readCarmen(clf);
  ASSERT_EQ(from_bag.entries.size(), from_clf.entries.size());
  for (std::size_t k : {std::size_t(0), std::size_t(5000), from_bag.entries.size() - 1}) {
    const LaserScan &a = from_bag.entries[k].scan, &b = from_clf.entries[k].scan;
    EXPECT_NEAR(a.stamp, b.stamp, 1e-3);
    ASSERT_EQ(a.ranges.size(), b.ranges.size());
    for (std::size_t n = 0; n < a.ranges.size(); ++n) {
      EXPECT_EQ(std::isnan(a.ranges[n]), std::isnan(b.ranges[n])) << "scan " << k << " beam " << n;
      if (!std::isnan(a.ranges[n])) {
        EXPECT_NEAR(a.ranges[n], b.ranges[n], 1e-3);
      }
    }
  }
  ASSERT_TRUE(from_bag.entries[5000].odometry.has_value());
  EXPECT_NEAR(from_bag.entries[5000].odometry->x, from_clf.entries[5000].odometry->x, 0.01);
}

}  // namespace
}  // namespace contour_reg::io
