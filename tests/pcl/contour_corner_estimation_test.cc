#include "contour_reg/contour_corner_estimation.h"

#include <algorithm>
#include <limits>
#include <random>

#include <gtest/gtest.h>
#include <pcl/console/print.h>

#include "contour_reg/cloud_conversions.h"
#include "scenes.h"

namespace contour_reg {
namespace {

pcl::PointCloud<pcl::PointXYZ>::Ptr toCloud(const LaserScan &scan) {
  auto cloud = pcl::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
  const ComplexSequence code = polarCode(scan);
  for (const Complex &c : code) cloud->push_back(pcl::PointXYZ(float(c.real()), float(c.imag()), 0.0f));
  cloud->is_dense = std::all_of(code.begin(), code.end(), [](const Complex &c) { return isFinite(c); });
  return cloud;
}

TEST(ContourCornerEstimation, GivesTheSameAnswerAsTheCore) {
  const test::RoomWithBoxes room;
  const LaserScan scan = test::scanFrom(room.world, test::pose2d(0.2, 0.1, 10), 0.01);
  const auto cloud = toCloud(scan);
  ContourCornerEstimation<pcl::PointXYZ> estimation;
  estimation.setInputCloud(cloud);
  pcl::PointCloud<ContourCorner> corners;
  estimation.compute(corners);

  // The core on the cloud's own (float) coordinates.
  const ContourFeatures expected = extractContourFeatures(polarCodeFromCloud(*cloud), ContourParams{});
  ASSERT_EQ(corners.size(), expected.special_points.size());
  ASSERT_GE(corners.size(), room.visibleCorners(test::pose2d(0.2, 0.1, 10)).size());
  EXPECT_EQ(corners.width, corners.size());
  EXPECT_TRUE(corners.is_dense);
  for (std::size_t k = 0; k < corners.size(); ++k) {
    const SpecialPoint &p = expected.special_points[k];
    EXPECT_FLOAT_EQ(corners[k].x, float(p.position.x()));
    EXPECT_FLOAT_EQ(corners[k].y, float(p.position.y()));
    EXPECT_FLOAT_EQ(corners[k].corner_angle, float(p.corner_angle));
    EXPECT_FLOAT_EQ(corners[k].orientation, float(p.orientation));
    EXPECT_FLOAT_EQ(corners[k].response, float(p.response));
    EXPECT_EQ(corners[k].turn, float(p.turn));
    EXPECT_FLOAT_EQ(corners[k].fragment[0], float(p.fragment[0].real()));
    EXPECT_FLOAT_EQ(corners[k].fragment[31], float(p.fragment[15].imag()));
  }
  EXPECT_EQ(estimation.getContourFeatures().special_points.size(), corners.size());
}

TEST(ContourCornerEstimation, WorksForPointXYZIAndShuffledDenseClouds) {
  const test::RoomWithBoxes room;
  const LaserScan scan = test::scanFrom(room.world, test::pose2d(0, 0, 0));
  const auto ordered = toCloud(scan);
  auto shuffled = pcl::make_shared<pcl::PointCloud<pcl::PointXYZI>>();
  for (const auto &p : *ordered)
    if (std::isfinite(p.x)) {
      pcl::PointXYZI q;
      q.x = p.x, q.y = p.y, q.z = 0.0f, q.intensity = 1.0f;
      shuffled->push_back(q);
    }
  std::mt19937 prng(42);
  std::shuffle(shuffled->begin(), shuffled->end(), prng);
  shuffled->is_dense = true;

  ContourCornerEstimation<pcl::PointXYZI> estimation;
  estimation.setInputCloud(shuffled);
  pcl::PointCloud<ContourCorner> corners;
  estimation.compute(corners);
  for (const Eigen::Vector2d &corner : room.visibleCorners(test::pose2d(0, 0, 0))) {
    const bool seen = std::any_of(corners.begin(), corners.end(), [&](const ContourCorner &c) {
      return (Eigen::Vector2d(c.x, c.y) - corner).norm() < 0.02;
    });
    EXPECT_TRUE(seen) << corner.transpose();
  }
}

ComplexSequence pointsAtBearings(double from_deg, double to_deg, double step_deg) {
  ComplexSequence points;
  for (double a = from_deg; step_deg > 0 ? a <= to_deg : a >= to_deg; a += step_deg)
    points.push_back(std::polar(2.0 + 0.01 * points.size(), a * M_PI / 180.0));
  return points;
}

TEST(CloudConversions, BearingOrderAllowsOneWrapAround) {
  EXPECT_TRUE(isInBearingOrder(pointsAtBearings(-135, 135, 0.25)));   // a 270-degree scan in beam order
  EXPECT_TRUE(isInBearingOrder(pointsAtBearings(90, 269, 1.0)));      // crosses +-180 once
  EXPECT_FALSE(isInBearingOrder(pointsAtBearings(135, -135, -0.25)));  // clockwise
  EXPECT_FALSE(isInBearingOrder(pointsAtBearings(0, 719, 10.0)));      // two full turns
  ComplexSequence swapped = pointsAtBearings(-90, 90, 1.0);
  std::swap(swapped[40], swapped[41]);
  EXPECT_FALSE(isInBearingOrder(swapped));
  sortByBearing(swapped);
  EXPECT_TRUE(isInBearingOrder(swapped));
  EXPECT_TRUE(isInBearingOrder({}));
}

TEST(ContourCornerEstimation, EmptyAndInvalidInputGiveEmptyOutput) {
  ContourCornerEstimation<pcl::PointXYZ> estimation;
  pcl::PointCloud<ContourCorner> corners;
  auto empty = pcl::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
  estimation.setInputCloud(empty);
  estimation.compute(corners);
  EXPECT_TRUE(corners.empty());

  auto all_nan = pcl::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  all_nan->resize(360, pcl::PointXYZ(nan, nan, nan));
  all_nan->is_dense = false;
  estimation.setInputCloud(all_nan);
  estimation.compute(corners);
  EXPECT_TRUE(corners.empty());

  // Misuse is reported the PCL way: an error and an empty output.
  const auto verbosity = pcl::console::getVerbosityLevel();
  pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
  estimation.setFragmentHalfLength(20);
  estimation.setInputCloud(toCloud(test::scanFrom(test::RoomWithBoxes().world, test::pose2d(0, 0, 0))));
  estimation.compute(corners);
  EXPECT_TRUE(corners.empty());
  pcl::console::setVerbosityLevel(verbosity);
}

}  // namespace
}  // namespace contour_reg
