// Motion hypotheses from the contours' direction and wall-offset histograms, and the local
// fallback that refines them when the corners cannot decide.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "contour_reg/core/direction_histogram.h"
#include "contour_reg/core/registration.h"
#include "contour_reg/core/transform_estimation.h"
#include "scenes.h"

namespace contour_reg {
namespace {

constexpr double kDeg = M_PI / 180.0;

ContourFeatures featuresFrom(const simulation::World &world, const Eigen::Isometry2d &pose, unsigned seed,
                             double noise = 0.01) {
  return extractContourFeatures(test::scanFrom(world, pose, noise, seed), ContourParams{});
}

// Registration with the corners set aside: every pair goes to the local fallback.
RegistrationResult registerWithoutCorners(const ContourFeatures &source, const ContourFeatures &target,
                                          bool direction_hypotheses) {
  RegistrationParams params;
  params.min_special_points = 1 << 20;
  params.direction_hypotheses = direction_hypotheses;
  std::mt19937 rng(5);
  return registerContours(source, target, params, rng);
}

TEST(DirectionHistogram, RectangularRoomPutsItsContourAtFourDirections) {
  const test::RoomWithBoxes room;
  const ContourFeatures features = featuresFrom(room.world, test::pose2d(0.3, 0.2, 0), 1, 0.0);
  const DirectionHistogramParams params;
  const std::vector<double> h = angleHistogram(features.contours, params);
  ASSERT_EQ(h.size(), 360u);
  double total = 0.0, near_walls = 0.0;
  for (int b = 0; b < 360; ++b) {
    const double angle = -180.0 + b + 0.5;  // bin centre, degrees
    const double off_axis = std::abs(std::remainder(angle, 90.0));
    total += h[b];
    if (off_axis <= 6.0) near_walls += h[b];
  }
  EXPECT_GT(near_walls / total, 0.9);
}

TEST(DirectionHistogram, HypothesesIncludeALargeMotion) {
  const test::RoomWithBoxes room;
  const Eigen::Isometry2d motion = test::pose2d(1.0, -0.4, 25);
  const ContourFeatures target = featuresFrom(room.world, test::pose2d(0, 0, 0), 2);
  const ContourFeatures source = featuresFrom(room.world, motion, 3);
  const std::vector<Eigen::Matrix3d> hypotheses = directionHypotheses(source, target, DirectionHistogramParams{});
  ASSERT_FALSE(hypotheses.empty());
  const Eigen::Matrix3d truth = motion.matrix();
  double nearest = INFINITY, nearest_turn = INFINITY;
  for (const Eigen::Matrix3d &h : hypotheses) {
    const double d = (h.topRightCorner<2, 1>() - truth.topRightCorner<2, 1>()).norm();
    if (d < nearest) {
      nearest = d;
      nearest_turn = std::abs(std::remainder(yawOf(h) - yawOf(truth), 2.0 * M_PI));
    }
  }
  EXPECT_LT(nearest, 0.15);
  EXPECT_LT(nearest_turn, 2.0 * kDeg);
}

TEST(DirectionHistogram, InvalidSettingsGiveNoHypotheses) {
  const test::RoomWithBoxes room;
  const ContourFeatures features = featuresFrom(room.world, test::pose2d(0, 0, 0), 4);
  DirectionHistogramParams params;
  params.offset_bin = 0.0;
  std::string why;
  EXPECT_FALSE(params.validate(&why));
  EXPECT_NE(why.find("offset"), std::string::npos);
  EXPECT_TRUE(directionHypotheses(features, features, params).empty());
}

TEST(LocalFallback, RecoversALargeMotionWithoutCornersFromTheDirections) {
  const test::RoomWithBoxes room;
  const Eigen::Isometry2d motion = test::pose2d(1.0, -0.4, 25);
  ContourFeatures target = featuresFrom(room.world, test::pose2d(0, 0, 0), 6);
  ContourFeatures source = featuresFrom(room.world, motion, 7);
  target.special_points.clear();  // scans in which no corner was found
  source.special_points.clear();
  const RegistrationResult r = registerWithoutCorners(source, target, true);
  ASSERT_TRUE(r.converged) << r.reason;
  EXPECT_TRUE(r.from_local_fallback);
  const Eigen::Matrix3d truth = motion.matrix();
  EXPECT_NEAR(r.transform(0, 2), truth(0, 2), 0.02);
  EXPECT_NEAR(r.transform(1, 2), truth(1, 2), 0.02);
  EXPECT_NEAR(std::remainder(yawOf(r.transform) - yawOf(truth), 2.0 * M_PI), 0.0, 0.5 * kDeg);

  // From the identity alone, 25 degrees and a metre off, the refinement cannot reach it.
  const RegistrationResult alone = registerWithoutCorners(source, target, false);
  EXPECT_FALSE(alone.converged) << alone.transform;
  EXPECT_FALSE(alone.reason.empty());
}

TEST(LocalFallback, SymmetricSceneIsReportedAmbiguous) {
  // An empty square room seen all round from its centre, then from the same spot turned by
  // 90 degrees: the two scans are alike, and standing still fits them as well as the turn.
  simulation::World room;
  room.addBox({-3.0, -3.0}, {3.0, 3.0});
  simulation::LidarModel all_round = simulation::LidarModel::ydlidarX4();
  all_round.dropout = 0.0;
  std::mt19937 rng(10);
  const ContourFeatures target =
      extractContourFeatures(simulation::simulateScan(room, test::pose2d(0, 0, 0), all_round, rng), ContourParams{});
  const ContourFeatures source =
      extractContourFeatures(simulation::simulateScan(room, test::pose2d(0, 0, 90), all_round, rng), ContourParams{});
  const RegistrationResult r = registerWithoutCorners(source, target, true);
  EXPECT_FALSE(r.converged) << r.transform;
  EXPECT_NE(r.reason.find("distinct motions fit equally well"), std::string::npos) << r.reason;
}

}  // namespace
}  // namespace contour_reg
