#include <cmath>

#include <gtest/gtest.h>

#include "contour_reg/io/carmen.h"
#include "contour_reg/io/read_log.h"
#include "contour_reg/io/rosbag.h"
#include "temp_dir.h"

namespace contour_reg::io {
namespace {

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
