#pragma once
// A small log of the kind a bag carries, for the bag readers' tests.

#include <cmath>

#include <gtest/gtest.h>

#include "contour_reg/io/scan_log.h"

namespace contour_reg::test {

// A log as a spinning LIDAR on a moving base records it: three scans of 4 beams, the second
// stopped (no timing), odometry with each.
inline io::ScanLog timedLog() {
  io::ScanLog log;
  for (int k = 0; k < 3; ++k) {
    io::LogEntry entry;
    entry.scan.stamp = 0.5 * k;  // the first at 0 s, as a simulated run starts
    entry.scan.angle_min = -1.0;
    entry.scan.angle_increment = 0.5;
    entry.scan.range_max = 30.0;
    entry.scan.time_increment = k == 1 ? 0.0 : 0.01;
    entry.scan.ranges = {1.0f, 2.0f, std::nanf(""), 4.0f + static_cast<float>(k)};
    entry.odometry = io::Pose2D{0.3 * k, -0.1 * k, 0.2 * k};
    log.entries.push_back(entry);
  }
  return log;
}

// Checks that `read`, a bag's timedLog() read back, holds its scans, timing and odometry.
inline void expectTimedLogReadBack(const io::ScanLog &read, const io::ScanLog &written) {
  EXPECT_TRUE(read.report.problems.empty()) << read.report.problems.front();
  ASSERT_EQ(read.entries.size(), written.entries.size());
  for (std::size_t k = 0; k < read.entries.size(); ++k) {
    const LaserScan &a = read.entries[k].scan, &b = written.entries[k].scan;
    EXPECT_NEAR(a.stamp, b.stamp, 1e-9);
    EXPECT_FLOAT_EQ(static_cast<float>(a.time_increment), static_cast<float>(b.time_increment)) << "scan " << k;
    EXPECT_FLOAT_EQ(static_cast<float>(a.angle_min), -1.0f);
    EXPECT_FLOAT_EQ(static_cast<float>(a.angle_increment), 0.5f);
    ASSERT_EQ(a.ranges.size(), 4u);
    EXPECT_FLOAT_EQ(a.ranges[3], b.ranges[3]);
    EXPECT_TRUE(std::isnan(a.ranges[2]));
    ASSERT_TRUE(read.entries[k].odometry.has_value());
    EXPECT_NEAR(read.entries[k].odometry->x, 0.3 * k, 1e-9);
    EXPECT_NEAR(read.entries[k].odometry->yaw, 0.2 * k, 1e-9);
  }
}

// Checks the odometry of the bag tests' one scan at 12.25 s, between the samples at 12 s (x 1.5)
// and 13 s (x 2.5), both at y -2 and 90 deg: a quarter of the way from one to the other.
inline void expectOdometryAQuarterOfTheWay(const io::ScanLog &log) {
  ASSERT_EQ(log.entries.size(), 1u);
  ASSERT_TRUE(log.entries[0].odometry.has_value());
  EXPECT_NEAR(log.entries[0].odometry->x, 1.75, 1e-9);
  EXPECT_NEAR(log.entries[0].odometry->y, -2.0, 1e-9);
  EXPECT_NEAR(log.entries[0].odometry->yaw, M_PI / 2, 1e-9);
  EXPECT_EQ(log.wheel_odometry.size(), 2u);
}

}  // namespace contour_reg::test
