#include <cmath>
#include <fstream>
#include <iterator>

#include <gtest/gtest.h>
#include <zlib.h>

#include "contour_reg/io/carmen.h"
#include "contour_reg/io/read_log.h"
#include "temp_dir.h"

namespace contour_reg::io {
namespace {

using test::TempDir;

// A FLASER line of n beams at range r, odometry pose (x, y, yaw) and a stamp.
std::string flaser(int n, double r, double x, double y, double yaw, double stamp) {
  std::string line = "FLASER " + std::to_string(n);
  for (int k = 0; k < n; ++k) line += " " + std::to_string(r);
  char tail[256];
  std::snprintf(tail, sizeof tail, " %f %f %f %f %f %f %f host %f\n", x, y, yaw, x, y, yaw, stamp, stamp);
  return line + tail;
}

TEST(Carmen, FlaserGivesBeamGeometryRangesOdometryAndStamp) {
  TempDir dir;
  const auto path = dir.write("a.clf", flaser(180, 2.5, 1.0, 2.0, 0.5, 10.0));
  const ScanLog log = readCarmen(path);
  ASSERT_EQ(log.entries.size(), 1u);
  const LaserScan &scan = log.entries[0].scan;
  EXPECT_EQ(scan.ranges.size(), 180u);
  EXPECT_NEAR(scan.angle_min, -M_PI / 2, 1e-12);
  EXPECT_NEAR(scan.angle_increment, M_PI / 180, 1e-12);
  EXPECT_FLOAT_EQ(scan.ranges[17], 2.5f);
  EXPECT_DOUBLE_EQ(scan.stamp, 10.0);
  ASSERT_TRUE(log.entries[0].odometry);
  EXPECT_DOUBLE_EQ(log.entries[0].odometry->y, 2.0);
}

// CARMEN lines carry no beam timing; a scan period gives it: 180 beams of 1 deg at 10 Hz are
// 1/3600 s apart. Without one the scans stay untimed.
TEST(Carmen, AScanPeriodGivesBeamTiming) {
  TempDir dir;
  const auto path = dir.write("a.clf", flaser(180, 2.5, 1.0, 2.0, 0.5, 10.0));
  EXPECT_EQ(readLog(path).entries.at(0).scan.time_increment, 0.0);
  LogReadOptions options;
  options.scan_period = 0.1;
  const LaserScan scan = readLog(path, options).entries.at(0).scan;
  EXPECT_NEAR(scan.time_increment, 0.1 / 360.0, 1e-12);
  EXPECT_DOUBLE_EQ(scan.stamp, 10.0);
}

// A beam step keeps every n-th beam from the first, as a LIDAR with n times the angular step
// gives them: 361 beams of 0.5 deg become 181 of 1 deg, beam k the original's beam 2k, and a
// scan period times the kept beams by their own spacing.
TEST(Carmen, ABeamStepKeepsEveryNthBeam) {
  TempDir dir;
  std::string line = "FLASER 361";
  for (int k = 0; k < 361; ++k) line += " " + std::to_string(1.0 + 0.01 * k);
  const auto path = dir.write("a.clf", line + " 0 0 0 0 0 0 10.0 host 10.0\n");
  LogReadOptions options;
  options.beam_step = 2;
  options.scan_period = 0.1;
  const LaserScan scan = readLog(path, options).entries.at(0).scan;
  ASSERT_EQ(scan.ranges.size(), 181u);
  EXPECT_NEAR(scan.angle_min, -M_PI / 2, 1e-12);
  EXPECT_NEAR(scan.angle_increment, M_PI / 180, 1e-12);
  EXPECT_NEAR(scan.bearing(180), M_PI / 2, 1e-12);
  EXPECT_FLOAT_EQ(scan.ranges[1], 1.02f);
  EXPECT_FLOAT_EQ(scan.ranges[180], 4.6f);
  EXPECT_NEAR(scan.time_increment, 0.1 / 360.0, 1e-12);
  options.beam_step = 0;
  EXPECT_THROW(readLog(path, options), std::invalid_argument);
}

TEST(Carmen, ReadingsAtMaxRangeAreNoReturn) {
  TempDir dir;
  const ScanLog log = readCarmen(dir.write("a.clf", flaser(4, 81.83, 0, 0, 0, 1.0)));
  for (float r : log.entries[0].scan.ranges) EXPECT_TRUE(std::isnan(r));
}

TEST(Carmen, OutOfOrderScansAreSortedAndCounted) {
  TempDir dir;
  const auto path =
      dir.write("a.clf", flaser(4, 1, 0, 0, 0, 3.0) + flaser(4, 1, 0, 0, 0, 1.0) + flaser(4, 1, 0, 0, 0, 2.0));
  const ScanLog log = readCarmen(path);
  ASSERT_EQ(log.entries.size(), 3u);
  EXPECT_DOUBLE_EQ(log.entries[0].scan.stamp, 1.0);
  EXPECT_DOUBLE_EQ(log.entries[2].scan.stamp, 3.0);
  EXPECT_EQ(log.report.reordered, 1u);
}

TEST(Carmen, RawLaserGetsOdometryInterpolatedFromOdomLines) {
  TempDir dir;
  const std::string text =
      "ODOM 0 0 0 0 0 0 10.0 host 10.0\n"
      "RAWLASER1 0 -1.5708 3.1416 0.0175 80 0.01 0 3 1.0 1.0 1.0 0 11.0 host 11.0\n"
      "ODOM 2 4 0.2 0 0 0 12.0 host 12.0\n";
  const ScanLog log = readCarmen(dir.write("a.clf", text));
  ASSERT_EQ(log.entries.size(), 1u);
  ASSERT_TRUE(log.entries[0].odometry);
  EXPECT_NEAR(log.entries[0].odometry->x, 1.0, 1e-9);
  EXPECT_NEAR(log.entries[0].odometry->y, 2.0, 1e-9);
  EXPECT_NEAR(log.entries[0].odometry->yaw, 0.1, 1e-9);
}

TEST(Carmen, BadAndTruncatedLinesAreSkippedAndNamedByFileAndLine) {
  TempDir dir;
  const std::string good = flaser(4, 1, 0, 0, 0, 1.0);
  const std::string text = good + "FLASER 4 1 1 nonsense 1 0 0 0 0 0 0 2.0 host 2.0\n" + "FLASER 999999999 1 2\n" +
                           flaser(4, 1, 0, 0, 0, 3.0) + "FLASER 4 1 1 1";  // truncated, no newline
  const auto path = dir.write("bad.clf", text);
  const ScanLog log = readCarmen(path);
  EXPECT_EQ(log.entries.size(), 2u);
  EXPECT_EQ(log.report.skipped, 3u);
  ASSERT_EQ(log.report.problems.size(), 3u);
  EXPECT_NE(log.report.problems[0].find(path + ":2:"), std::string::npos) << log.report.problems[0];
  EXPECT_NE(log.report.problems[1].find("absurd beam count"), std::string::npos) << log.report.problems[1];
  EXPECT_NE(log.report.problems[2].find(":5:"), std::string::npos) << log.report.problems[2];
}

TEST(Carmen, NanAndInfRangesBecomeInvalidBeams) {
  TempDir dir;
  const ScanLog log = readCarmen(dir.write("a.clf", "FLASER 4 1.0 nan inf -1 0 0 0 0 0 0 5.0 host 5.0\n"));
  ASSERT_EQ(log.entries.size(), 1u);
  const auto &r = log.entries[0].scan.ranges;
  EXPECT_FLOAT_EQ(r[0], 1.0f);
  EXPECT_TRUE(std::isnan(r[1]) && std::isnan(r[2]) && std::isnan(r[3]));
}

// Found by tests/fuzz: a NaN remission count was cast to an integer.
TEST(Carmen, NonNumericCountsInRobotLaserLinesAreSkipped) {
  TempDir dir;
  const std::string robotlaser = "ROBOTLASER1 0 -1.5 3.0 1.0 30 0.01 0 4 1 2 3 4 ";
  const std::string tail = " 0 0 0 0 0 0 0 0 0 0 0 1.0 host 1.0\n";
  const auto path = dir.write("r.clf", robotlaser + "0" + tail + robotlaser + "nan" + tail + robotlaser + "inf" + tail);
  const ScanLog log = readCarmen(path);
  EXPECT_EQ(log.entries.size(), 1u);
  EXPECT_EQ(log.report.skipped, 2u);
  ASSERT_FALSE(log.report.problems.empty());
  EXPECT_NE(log.report.problems[0].find(path + ":2:"), std::string::npos) << log.report.problems[0];
}

TEST(Carmen, FilesWithoutAUsableScanAreErrorsNamingTheFile) {
  TempDir dir;
  for (const std::string &text : {std::string(), std::string("ODOM 0 0 0 0 0 0 1 h 1\n"),
                                  std::string("\x7f\x45\x4c\x46\x02\x01\x01\0\0\0garbage\xff\xfe", 20)}) {
    const auto path = dir.write("empty.clf", text);
    try {
      readCarmen(path);
      FAIL() << "no error for " << path;
    } catch (const ReadError &error) {
      EXPECT_NE(std::string(error.what()).find(path), std::string::npos);
    }
  }
  EXPECT_THROW(readCarmen(dir.file("missing.clf")), ReadError);
}

TEST(Carmen, GzipLogsReadLikePlainOnes) {
  TempDir dir;
  const std::string text = flaser(6, 1.5, 0, 0, 0, 1.0) + flaser(6, 1.7, 0.1, 0, 0, 2.0);
  gzFile file = gzopen(dir.file("a.clf.gz").c_str(), "wb");
  gzwrite(file, text.data(), static_cast<unsigned>(text.size()));
  gzclose(file);
  const ScanLog plain = readCarmen(dir.write("a.clf", text)), zipped = readCarmen(dir.file("a.clf.gz"));
  ASSERT_EQ(zipped.entries.size(), 2u);
  EXPECT_EQ(zipped.entries[1].scan.ranges, plain.entries[1].scan.ranges);
}

// A gzip log cut short (a copy that stopped) or corrupt ends where zlib stops; the reader said
// nothing of it and read the scans before as the whole log. It names where the rest was lost.
TEST(Carmen, AGzipLogCutShortIsNamed) {
  TempDir dir;
  std::string text;
  for (int k = 0; k < 400; ++k) text += flaser(6, 1.5 + 0.001 * k, 0, 0, 0, 1.0 + k);
  gzFile file = gzopen(dir.file("a.clf.gz").c_str(), "wb");
  gzwrite(file, text.data(), static_cast<unsigned>(text.size()));
  gzclose(file);
  const std::string zipped = test::readBytes(dir.file("a.clf.gz"));
  const std::string path = dir.write("cut.clf.gz", zipped.substr(0, zipped.size() / 2));
  const ScanLog read = readCarmen(path);
  EXPECT_GT(read.entries.size(), 0u);
  EXPECT_LT(read.entries.size(), 400u);
  ASSERT_FALSE(read.report.problems.empty());
  EXPECT_NE(read.report.problems.back().find("the rest is not read"), std::string::npos) << read.report.problems.back();
  EXPECT_NE(read.report.problems.back().find(path + ":"), std::string::npos) << read.report.problems.back();
}

TEST(Carmen, WrittenLogsReadBackWithBeamGeometry) {
  TempDir dir;
  ScanLog log;
  LogEntry entry;
  entry.scan.stamp = 4.25;
  entry.scan.angle_min = -2.0;
  entry.scan.angle_increment = 0.01;
  entry.scan.range_max = 30.0;
  entry.scan.ranges = {1.0f, std::nanf(""), 2.5f, 3.25f};
  entry.odometry = Pose2D{1.5, -2.0, 0.3};
  log.entries.push_back(entry);
  writeCarmen(dir.file("w.clf"), log);
  const ScanLog back = readLog(dir.file("w.clf"));
  ASSERT_EQ(back.entries.size(), 1u);
  const LaserScan &s = back.entries[0].scan;
  EXPECT_NEAR(s.angle_min, -2.0, 1e-9);
  EXPECT_NEAR(s.angle_increment, 0.01, 1e-9);
  EXPECT_NEAR(s.stamp, 4.25, 1e-6);
  EXPECT_FLOAT_EQ(s.ranges[3], 3.25f);
  EXPECT_TRUE(std::isnan(s.ranges[1]));
  EXPECT_NEAR(back.entries[0].odometry->yaw, 0.3, 1e-6);
}

// ODOM lines are written for every wheel odometry sample of the log, between the scans too.
TEST(Carmen, WrittenLogsKeepTheWheelOdometryBetweenTheScans) {
  TempDir dir;
  ScanLog log;
  for (int k = 0; k < 2; ++k) {
    LogEntry entry;
    entry.scan.stamp = 1.0 + k;
    entry.scan.angle_increment = 0.01;
    entry.scan.ranges = {1.0f, 2.0f};
    entry.odometry = Pose2D{0.5 * k, 0.0, 0.1 * k};
    log.entries.push_back(entry);
  }
  for (int i = 0; i <= 4; ++i) log.wheel_odometry.push_back({1.0 + 0.25 * i, Pose2D{0.125 * i, 0.0, 0.025 * i}});
  writeCarmen(dir.file("w.clf"), log);
  const ScanLog back = readLog(dir.file("w.clf"));
  ASSERT_EQ(back.wheel_odometry.size(), 5u);
  EXPECT_NEAR(back.wheel_odometry[2].stamp, 1.5, 1e-6);
  EXPECT_NEAR(back.wheel_odometry[2].pose.x, 0.25, 1e-6);
  EXPECT_NEAR(back.wheel_odometry[3].pose.yaw, 0.075, 1e-6);
}

// A ROBOTLASER1 line carries the laser's pose and the robot's: their difference in the robot's
// frame is where the laser is mounted. The robot at (1, 2) facing +y with the laser 0.25 m
// ahead of it and turned 10 deg: the laser at (1, 2.25), yaw 100 deg.
TEST(Carmen, RobotLaserLinesGiveTheMounting) {
  TempDir dir;
  const double deg = M_PI / 180.0;
  char line[512];
  std::snprintf(line, sizeof line,
                "ROBOTLASER1 0 -1.5 3.0 1.0 30 0.01 0 4 1.0 2.0 3.0 4.0 0 %f %f %f %f %f %f 0 0 0 0 0 7.5 host 7.5\n",
                1.0, 2.25, 100 * deg, 1.0, 2.0, 90 * deg);
  const ScanLog log = readCarmen(dir.write("mounted.log", line));
  ASSERT_EQ(log.entries.size(), 1u);
  ASSERT_TRUE(log.laser_pose.has_value());
  EXPECT_NEAR(log.laser_pose->x, 0.25, 1e-6);
  EXPECT_NEAR(log.laser_pose->y, 0.0, 1e-6);
  EXPECT_NEAR(log.laser_pose->yaw, 10 * deg, 1e-6);
  EXPECT_NEAR(log.entries[0].odometry->y, 2.0, 1e-9);  // the robot's pose
  // FLASER lines say nothing of it; --laser-pose (LogReadOptions::laser_pose) does.
  const std::string flaser_log = dir.write("f.clf", flaser(180, 2.5, 1.0, 2.0, 0.5, 10.0));
  EXPECT_FALSE(readLog(flaser_log).laser_pose.has_value());
  LogReadOptions options;
  options.laser_pose = Pose2D{-0.04, 0.0, 0.0};
  EXPECT_DOUBLE_EQ(readLog(flaser_log, options).laser_pose->x, -0.04);
  EXPECT_DOUBLE_EQ(readLog(dir.file("mounted.log"), options).laser_pose->x, -0.04);
  // A written log keeps it.
  ScanLog mounted = log;
  mounted.laser_pose = Pose2D{0.3, -0.1, -0.5};
  writeCarmen(dir.file("w.log"), mounted);
  const ScanLog back = readCarmen(dir.file("w.log"));
  ASSERT_TRUE(back.laser_pose.has_value());
  EXPECT_NEAR(back.laser_pose->x, 0.3, 1e-6);
  EXPECT_NEAR(back.laser_pose->y, -0.1, 1e-6);
  EXPECT_NEAR(back.laser_pose->yaw, -0.5, 1e-6);
}

// A mounting 1e300 m from the robot (a corrupt line) would put every pose of the robot there:
// an error naming the file, unless the user gives the mounting.
TEST(Carmen, AMountingNoRobotCarriesIsAnError) {
  TempDir dir;
  const std::string path = dir.write(
      "far.log", "ROBOTLASER1 0 -1.5 3.0 1.0 30 0.01 0 4 1.0 2.0 3.0 4.0 0 1e300 2 0 1 2 0 0 0 0 0 0 7.5 host 7.5\n");
  try {
    readLog(path);
    FAIL() << "a laser 1e300 m from the robot must be refused";
  } catch (const ReadError &error) {
    EXPECT_NE(std::string(error.what()).find("far.log: the log mounts the laser 1e+300 m"), std::string::npos)
        << error.what();
  }
  LogReadOptions options;
  options.laser_pose = Pose2D{0.2, 0.0, 0.0};
  EXPECT_DOUBLE_EQ(readLog(path, options).laser_pose->x, 0.2);
}

TEST(Carmen, SharedLogsRead) {
  const std::string path = test::sharedDataset("intel/intel.clf");
  if (path.empty()) GTEST_SKIP() << "../shared/datasets/intel is absent";
  const ScanLog log = readCarmen(path);
  EXPECT_EQ(log.entries.size(), 13631u);
  EXPECT_EQ(log.entries[0].scan.ranges.size(), 180u);
  EXPECT_TRUE(log.entries[100].odometry.has_value());
}

}  // namespace
}  // namespace contour_reg::io
