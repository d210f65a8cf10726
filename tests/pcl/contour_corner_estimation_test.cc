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

bool isNoCorner(const ContourCorner &c) {
  return std::isnan(c.x) && std::isnan(c.y) && std::isnan(c.z) && std::isnan(c.corner_angle) &&
         std::isnan(c.response) && std::isnan(c.fragment[0]) && std::isnan(c.fragment[31]);
}

// pcl::Feature's contract: one output point per input point; the point nearest each corner
// carries it, every other point is NaN.
TEST(ContourCornerEstimation, GivesOneOutputPerInputPointWithTheCoresCorners) {
  const test::RoomWithBoxes room;
  const LaserScan scan = test::scanFrom(room.world, test::pose2d(0.2, 0.1, 10), 0.01);
  const auto cloud = toCloud(scan);
  ContourCornerEstimation<pcl::PointXYZ> estimation;
  estimation.setInputCloud(cloud);
  pcl::PointCloud<ContourCorner> corners;
  estimation.compute(corners);
  ASSERT_EQ(corners.size(), cloud->size());
  EXPECT_EQ(corners.width, corners.size());
  EXPECT_FALSE(corners.is_dense);

  // The core on the cloud's own (float) coordinates.
  const ContourFeatures expected = extractContourFeatures(polarCodeFromCloud(*cloud), ContourParams{});
  const pcl::Indices &indices = estimation.getCornerIndices();
  ASSERT_EQ(indices.size(), expected.special_points.size());
  ASSERT_GE(indices.size(), room.visibleCorners(test::pose2d(0.2, 0.1, 10)).size());
  for (std::size_t k = 0; k < indices.size(); ++k) {
    SCOPED_TRACE(k);
    const SpecialPoint &p = expected.special_points[k];
    ASSERT_GE(indices[k], 0);
    const ContourCorner &c = corners[static_cast<std::size_t>(indices[k])];
    // The carrying point is the scan point nearest the vertex: within a beam's spacing.
    const pcl::PointXYZ &raw = (*cloud)[static_cast<std::size_t>(indices[k])];
    EXPECT_LT((Eigen::Vector2d(raw.x, raw.y) - p.position).norm(), 0.06);
    EXPECT_FLOAT_EQ(c.x, float(p.position.x()));
    EXPECT_FLOAT_EQ(c.y, float(p.position.y()));
    EXPECT_FLOAT_EQ(c.corner_angle, float(p.corner_angle));
    EXPECT_FLOAT_EQ(c.orientation, float(p.orientation));
    EXPECT_FLOAT_EQ(c.response, float(p.response));
    EXPECT_EQ(c.turn, float(p.turn));
    EXPECT_FLOAT_EQ(c.fragment[0], float(p.fragment[0].real()));
    EXPECT_FLOAT_EQ(c.fragment[31], float(p.fragment[15].imag()));
  }
  const auto carrying =
      std::count_if(corners.begin(), corners.end(), [](const ContourCorner &c) { return !isNoCorner(c); });
  EXPECT_EQ(static_cast<std::size_t>(carrying), indices.size());  // and every other point is NaN in every field
  EXPECT_EQ(estimation.getContourFeatures().special_points.size(), indices.size());
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
  ASSERT_EQ(corners.size(), shuffled->size());
  for (const Eigen::Vector2d &corner : room.visibleCorners(test::pose2d(0, 0, 0))) {
    const bool seen = std::any_of(corners.begin(), corners.end(), [&](const ContourCorner &c) {
      return (Eigen::Vector2d(c.x, c.y) - corner).norm() < 0.02;
    });
    EXPECT_TRUE(seen) << corner.transpose();
  }
  // Sorting by bearing does not lose track of which input point carries a corner.
  for (const int index : estimation.getCornerIndices()) {
    const auto k = static_cast<std::size_t>(index);
    EXPECT_LT(
        (Eigen::Vector2d((*shuffled)[k].x, (*shuffled)[k].y) - Eigen::Vector2d(corners[k].x, corners[k].y)).norm(),
        0.06);
  }
}

TEST(ContourCornerEstimation, IndicesSelectTheOutputPointsAndOtherPointTypesGetTheSharedFields) {
  const test::RoomWithBoxes room;
  const auto cloud = toCloud(test::scanFrom(room.world, test::pose2d(0, 0, 0)));
  auto half = pcl::make_shared<pcl::Indices>();
  for (std::size_t n = 0; n < cloud->size() / 2; ++n) half->push_back(static_cast<int>(n));

  ContourCornerEstimation<pcl::PointXYZ> estimation;
  estimation.setInputCloud(cloud);
  estimation.setIndices(half);
  pcl::PointCloud<ContourCorner> corners;
  estimation.compute(corners);
  ASSERT_EQ(corners.size(), half->size());
  ASSERT_FALSE(estimation.getCornerIndices().empty());
  for (const int index : estimation.getCornerIndices()) EXPECT_LT(static_cast<std::size_t>(index), half->size());

  // The same corners as a plain pcl::PointXYZ cloud: the vertex only.
  ContourCornerEstimation<pcl::PointXYZ, pcl::PointXYZ> vertices;
  vertices.setInputCloud(cloud);
  vertices.setIndices(half);
  pcl::PointCloud<pcl::PointXYZ> out;
  vertices.compute(out);
  ASSERT_EQ(out.size(), half->size());
  EXPECT_EQ(vertices.getCornerIndices(), estimation.getCornerIndices());
  for (std::size_t k = 0; k < out.size(); ++k) {
    if (std::isnan(corners[k].x)) {
      EXPECT_TRUE(std::isnan(out[k].x));
    } else {
      EXPECT_EQ(out[k].x, corners[k].x);
      EXPECT_EQ(out[k].y, corners[k].y);
    }
  }
}

ComplexSequence pointsAtBearings(double from_deg, double to_deg, double step_deg) {
  ComplexSequence points;
  for (double a = from_deg; step_deg > 0 ? a <= to_deg : a >= to_deg; a += step_deg)
    points.push_back(std::polar(2.0 + 0.01 * points.size(), a * M_PI / 180.0));
  return points;
}

TEST(CloudConversions, BearingOrderAllowsOneWrapAround) {
  EXPECT_TRUE(isInBearingOrder(pointsAtBearings(-135, 135, 0.25)));    // a 270-degree scan in beam order
  EXPECT_TRUE(isInBearingOrder(pointsAtBearings(90, 269, 1.0)));       // crosses +-180 once
  EXPECT_FALSE(isInBearingOrder(pointsAtBearings(135, -135, -0.25)));  // clockwise
  EXPECT_FALSE(isInBearingOrder(pointsAtBearings(0, 719, 10.0)));      // two full turns
  ComplexSequence swapped = pointsAtBearings(-90, 90, 1.0);
  std::swap(swapped[40], swapped[41]);
  EXPECT_FALSE(isInBearingOrder(swapped));
  sortByBearing(swapped);
  EXPECT_TRUE(isInBearingOrder(swapped));
  EXPECT_TRUE(isInBearingOrder({}));
}

TEST(ContourCornerEstimation, EmptyInvalidAndCornerlessInputGiveNoCorner) {
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
  ASSERT_EQ(corners.size(), all_nan->size());
  EXPECT_TRUE(std::all_of(corners.begin(), corners.end(), isNoCorner));
  EXPECT_TRUE(estimation.getCornerIndices().empty());

  // Misuse is reported the PCL way: an error and an empty output.
  const auto verbosity = pcl::console::getVerbosityLevel();
  pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
  estimation.setFragmentHalfLength(20);
  estimation.setInputCloud(toCloud(test::scanFrom(test::RoomWithBoxes().world, test::pose2d(0, 0, 0))));
  estimation.compute(corners);
  EXPECT_TRUE(corners.empty());
  // Indices that name no point of the cloud (a negative one, one past its end).
  estimation.setFragmentHalfLength(ContourParams().special_points.fragment_half_length);
  const auto cloud = toCloud(test::scanFrom(test::RoomWithBoxes().world, test::pose2d(0, 0, 0)));
  estimation.setInputCloud(cloud);
  for (const int outside : {-1, static_cast<int>(cloud->size()), 1 << 30}) {
    auto indices = pcl::make_shared<pcl::Indices>();
    for (int n = 0; n < 100; ++n) indices->push_back(n);
    indices->push_back(outside);
    estimation.setIndices(indices);
    estimation.compute(corners);
    EXPECT_TRUE(corners.empty()) << outside;
  }
  pcl::console::setVerbosityLevel(verbosity);
}

}  // namespace
}  // namespace contour_reg
