#include "contour_reg/core/special_points.h"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "contour_reg/core/contour_features.h"
#include "scenes.h"

namespace contour_reg {
namespace {

constexpr double kDeg = M_PI / 180.0;

// The special point nearest to `expected`, or nullptr.
const SpecialPoint *nearest(const std::vector<SpecialPoint> &points, const Eigen::Vector2d &expected) {
  const SpecialPoint *best = nullptr;
  for (const SpecialPoint &p : points)
    if (!best || (p.position - expected).norm() < (best->position - expected).norm()) best = &p;
  return best;
}

void expectCornersSeen(const Eigen::Isometry2d &pose, double noise, double position_tolerance,
                       double angle_tolerance_deg) {
  const test::RoomWithBoxes room;
  const ContourFeatures features = extractContourFeatures(test::scanFrom(room.world, pose, noise), ContourParams{});
  const std::vector<Eigen::Vector2d> visible = room.visibleCorners(pose);
  ASSERT_GE(visible.size(), 3u);
  for (const Eigen::Vector2d &expected : visible) {
    const SpecialPoint *found = nearest(features.special_points, expected);
    ASSERT_NE(found, nullptr);
    EXPECT_LT((found->position - expected).norm(), position_tolerance)
        << "corner " << expected.transpose() << " seen at " << found->position.transpose();
    EXPECT_NEAR(found->corner_angle, 90 * kDeg, angle_tolerance_deg * kDeg);
  }
  // The room has no other corners: every special point is one of them.
  for (const SpecialPoint &p : features.special_points) {
    double distance = std::numeric_limits<double>::infinity();
    for (const Eigen::Vector2d &c : visible) distance = std::min(distance, (c - p.position).norm());
    EXPECT_LT(distance, 0.1) << "spurious special point at " << p.position.transpose();
  }
}

TEST(SpecialPoints, RoomWithBoxesGivesItsVisibleCorners) { expectCornersSeen(test::pose2d(0, 0, 0), 0.0, 0.02, 3.0); }

TEST(SpecialPoints, MovingAndTurningTheSensorMovesTheCorners) {
  expectCornersSeen(test::pose2d(0.4, -0.3, 20), 0.0, 0.02, 3.0);
  expectCornersSeen(test::pose2d(-0.5, 0.6, -25), 0.0, 0.02, 3.0);
}

TEST(SpecialPoints, CornersSurviveOneCentimetreRangeNoise) {
  for (unsigned seed : {1u, 2u, 3u}) {
    SCOPED_TRACE(seed);
    const test::RoomWithBoxes room;
    const auto pose = test::pose2d(0.1, 0.2, 5);
    const ContourFeatures features =
        extractContourFeatures(test::scanFrom(room.world, pose, 0.01, seed), ContourParams{});
    for (const Eigen::Vector2d &expected : room.visibleCorners(pose)) {
      const SpecialPoint *found = nearest(features.special_points, expected);
      ASSERT_NE(found, nullptr);
      EXPECT_LT((found->position - expected).norm(), 0.04);
      EXPECT_NEAR(found->corner_angle, 90 * kDeg, 5 * kDeg);
    }
  }
}

TEST(SpecialPoints, CarryOrientationTurnAndFragment) {
  const test::RoomWithBoxes room;
  const ContourParams params;
  const ContourFeatures features = extractContourFeatures(test::scanFrom(room.world, test::pose2d(0, 0, 0)), params);
  const SpecialPoint *room_corner = nearest(features.special_points, {6.0, 4.0});
  const SpecialPoint *box_corner = nearest(features.special_points, {-0.5, -1.2});
  ASSERT_TRUE(room_corner && box_corner);
  // Both corners have arms along -x and -y from the vertex: the bisector between the arms
  // points to -135 degrees (into the room for the concave corner, into the box for the convex one).
  EXPECT_NEAR(room_corner->orientation, -135 * kDeg, 2 * kDeg);
  EXPECT_NEAR(box_corner->orientation, -135 * kDeg, 2 * kDeg);
  EXPECT_NE(room_corner->turn, box_corner->turn);  // concave and convex turn opposite ways
  EXPECT_EQ(room_corner->fragment.size(), 2u * params.special_points.fragment_half_length);
  EXPECT_GT(room_corner->response, params.special_points.threshold);
}

LaserScan emptyLike(std::size_t beams, float value) {
  LaserScan scan;
  scan.angle_min = -M_PI / 2;
  scan.angle_increment = M_PI / 180;
  scan.range_max = 30.0;
  scan.ranges.assign(beams, value);
  return scan;
}

TEST(SpecialPoints, EmptyAllInvalidAndStraightWallGiveNone) {
  EXPECT_TRUE(extractContourFeatures(emptyLike(0, 1.0f), ContourParams{}).special_points.empty());
  EXPECT_TRUE(extractContourFeatures(emptyLike(181, std::numeric_limits<float>::quiet_NaN()), ContourParams{})
                  .special_points.empty());
  EXPECT_TRUE(extractContourFeatures(emptyLike(181, std::numeric_limits<float>::infinity()), ContourParams{})
                  .special_points.empty());
  simulation::World wall;
  wall.addSegment({3.0, -20.0}, {3.0, 20.0});
  const ContourFeatures features =
      extractContourFeatures(test::scanFrom(wall, test::pose2d(0, 0, 0), 0.01), ContourParams{});
  EXPECT_EQ(features.segments.size(), 1u);
  EXPECT_TRUE(features.special_points.empty());
}

TEST(SpecialPoints, PaperEqualizationFindsTheCornersToo) {
  ContourParams params;
  params.equalization.mode = EqualizationMode::kFixedCount;
  params.equalization.count = 600;
  const test::RoomWithBoxes room;
  const ContourFeatures features = extractContourFeatures(test::scanFrom(room.world, test::pose2d(0, 0, 0)), params);
  for (const Eigen::Vector2d &corner : room.visibleCorners(test::pose2d(0, 0, 0))) {
    const SpecialPoint *found = nearest(features.special_points, corner);
    ASSERT_NE(found, nullptr);
    EXPECT_LT((found->position - corner).norm(), 0.05);
  }
}

}  // namespace
}  // namespace contour_reg
