#include "contour_reg/core/free_space.h"

#include <gtest/gtest.h>

#include "contour_reg/core/transform_estimation.h"
#include "scenes.h"

namespace contour_reg {
namespace {

ContourFeatures featuresFrom(const simulation::World &world, const Eigen::Isometry2d &pose, unsigned seed) {
  return extractContourFeatures(test::scanFrom(world, pose, 0.01, seed), ContourParams{});
}

Eigen::Matrix3d motionBetween(const Eigen::Isometry2d &target, const Eigen::Isometry2d &source) {
  const Eigen::Isometry2d m = target.inverse() * source;
  return rigidTransform(m.translation().x(), m.translation().y(), std::atan2(m.linear()(1, 0), m.linear()(0, 0)));
}

FreeSpaceEvidence evidenceAt(const ContourFeatures &source, const ContourFeatures &target, const Eigen::Matrix3d &m,
                             const FreeSpaceParams &params = {}) {
  return mutualFreeSpaceEvidence(source, RangeView(source), target, RangeView(target), m, params);
}

TEST(FreeSpace, RefutesAMotionOnePeriodOffAlongARowOfDoors) {
  const simulation::World corridor = test::corridorOfDoors();
  const Eigen::Isometry2d target_pose = test::pose2d(0, 0, 0), source_pose = test::pose2d(0.5, 0.05, 2);
  const ContourFeatures target = featuresFrom(corridor, target_pose, 1),
                        source = featuresFrom(corridor, source_pose, 2);
  const Eigen::Matrix3d truth = motionBetween(target_pose, source_pose);
  const Eigen::Matrix3d alias = rigidTransform(truth(0, 2) - 3.0, truth(1, 2), yawOf(truth));  // one door back

  const FreeSpaceEvidence right = evidenceAt(source, target, truth);
  const FreeSpaceEvidence wrong = evidenceAt(source, target, alias);
  EXPECT_GT(right.tested_length, 10.0);
  EXPECT_EQ(right.contradicted_length, 0.0);
  // The source's end wall lands 3 m short of where the target saw it: the target looked through it.
  EXPECT_GT(wrong.contradicted_length, 2.0);
  EXPECT_GT(wrong.fraction(), 0.04);  // a few percent of both contours
  EXPECT_GE(wrong.contradicted_runs, 1);
}

TEST(FreeSpace, APersonWalkingThroughDoesNotRefuteTheRightMotion) {
  const simulation::World room = simulation::makeFurnishedRoom();
  simulation::World with_person = room;
  with_person.addCircle({0.9, -0.2}, 0.2);  // someone standing in the source scan only
  const Eigen::Isometry2d target_pose = test::pose2d(0.0, -0.4, 10), source_pose = test::pose2d(0.3, -0.3, 14);
  const ContourFeatures target = featuresFrom(room, target_pose, 1), source = featuresFrom(with_person, source_pose, 2);
  const Eigen::Matrix3d truth = motionBetween(target_pose, source_pose);

  FreeSpaceParams every_object;
  every_object.min_object_length = 0.0;
  // The person's outline lies where the target saw free space ...
  EXPECT_GT(evidenceAt(source, target, truth, every_object).contradicted_length, 0.2);
  // ... but an object that small may have moved between the scans: no evidence against the motion.
  EXPECT_EQ(evidenceAt(source, target, truth).contradicted_length, 0.0);
}

// A wall seen through a gap in a nearer one: a wrong motion puts most of the source's near
// wall behind the target's (hidden, no evidence) and only the stretch in line with the gap in
// front of the far wall the target saw through it. That stretch is short, but it lies on a
// wall, not on an object that may have moved: it counts.
TEST(FreeSpace, AShortStretchOfAWallInFreeSpaceCounts) {
  simulation::World world;
  world.addSegment({6.0, -6.0}, {6.0, 6.0});    // the far wall
  world.addSegment({3.0, -3.0}, {3.0, -0.12});  // the near wall, with a gap 0.24 m wide ...
  world.addSegment({3.0, 0.12}, {3.0, 3.0});    // ... straight ahead
  const Eigen::Isometry2d pose = test::pose2d(0, 0, 0);
  const ContourFeatures target = featuresFrom(world, pose, 1), source = featuresFrom(world, pose, 2);
  const RangeView target_view(target);
  const Eigen::Matrix3d wrong = rigidTransform(1.0, 0.5, 0.0);

  const FreeSpaceEvidence evidence = freeSpaceEvidence(source, target_view, wrong, FreeSpaceParams{});
  EXPECT_GT(evidence.contradicted_length, 0.2);  // the near wall in line with the gap, moved 1 m back
  EXPECT_LT(evidence.contradicted_length, 0.5);  // no more: the rest lies behind the target's near wall
  EXPECT_EQ(evidence.contradicted_runs, 1);
  EXPECT_EQ(freeSpaceEvidence(source, target_view, Eigen::Matrix3d::Identity(), FreeSpaceParams{}).contradicted_length,
            0.0);
}

// A wall in line with the source's beam: the source's beams pass along it, not through it, and
// the target sees it broadside. The right motion puts the target's wall on the source's beam,
// metres in front of that beam's return, yet the source never saw through the wall.
TEST(FreeSpace, AWallSeenEdgeOnDoesNotRefuteTheRightMotion) {
  simulation::World world;
  world.addSegment({10.0, -6.0}, {10.0, 6.0});  // a back wall the beams along the side wall reach
  world.addSegment({2.0, 0.0}, {6.0, 0.0});     // a side wall on the source's beam at bearing 0
  const Eigen::Isometry2d target_pose = test::pose2d(0, -3, 0), source_pose = test::pose2d(0, 0, 0);
  const ContourFeatures target = featuresFrom(world, target_pose, 1), source = featuresFrom(world, source_pose, 2);
  const Eigen::Matrix3d truth = motionBetween(target_pose, source_pose);

  const RangeView source_view(source);
  EXPECT_NEAR(source_view.rangeAt(0.0), 10.0, 0.1);  // the source's beam passed along the side wall
  const FreeSpaceEvidence along = freeSpaceEvidence(target, source_view, rigidInverse(truth), FreeSpaceParams{});
  EXPECT_GT(along.tested_length, 3.0);        // the side wall was checked against the source's beams ...
  EXPECT_EQ(along.contradicted_length, 0.0);  // ... and passes
  EXPECT_EQ(evidenceAt(source, target, truth).contradicted_length, 0.0);
}

// The range view finds the returns that bracket a point by approximateAtan2, the index and the
// query alike: that needs its stated bound and, for the order of bearings, monotonicity.
TEST(FreeSpace, ApproximateBearingIsWithinItsBoundAndKeepsBearingOrder) {
  double worst = 0.0, last = -M_PI;
  for (int k = 1; k < 200000; ++k) {
    const double bearing = -M_PI + 2.0 * M_PI * k / 200000.0;
    const double approximate = approximateAtan2(std::sin(bearing), std::cos(bearing));
    worst = std::max(worst, std::abs(approximate - bearing));
    EXPECT_GE(approximate, last) << "at " << bearing;
    last = approximate;
  }
  EXPECT_LT(worst, 2.1e-4);
  EXPECT_GT(worst, 1.9e-4);  // the bound is tight: no tighter one may be promised
}

TEST(FreeSpace, TheSurfaceBetweenTwoReturnsIsTheSegmentBetweenThem) {
  // A wall along y = 1.2 seen from the origin by beams 1 deg apart: 8 m ahead they meet it at
  // 8.5 deg, and two neighbouring returns lie about 0.9 m apart along it.
  ComplexSequence returns;
  for (int k = 1; k <= 80; ++k) {
    const double bearing = k * M_PI / 180.0;
    returns.emplace_back(1.2 / std::tan(bearing), 1.2);
  }
  RangeView view;
  view.assign(returns);
  EXPECT_LT(view.distanceToSurface(Eigen::Vector2d(8.0, 1.2)), 1e-9);           // on the wall between two returns
  EXPECT_NEAR(view.distanceToSurface(Eigen::Vector2d(8.0, 1.15)), 0.05, 1e-9);  // 5 cm in front of it
  EXPECT_LT(view.distanceToSurface(Eigen::Vector2d(-1.0, 0.0)), 0.0);           // behind the sensor: no returns there
  // A point on the wall lies up to 0.9 m behind the nearer of the two returns around its
  // bearing, the range the view measures there: beyond a free-space margin, hidden.
  EXPECT_EQ(view.sightOf(Eigen::Vector2d(8.45, 1.2), 0.3), RangeView::Sight::kHidden);
}

TEST(FreeSpace, BearingsWithoutReturnsGiveNoEvidence) {
  simulation::World wall;  // one wall ahead: no return at most bearings
  wall.addSegment({3.0, -1.0}, {3.0, 1.0});
  const ContourFeatures scan = featuresFrom(wall, test::pose2d(0, 0, 0), 1);
  const RangeView view(scan);
  EXPECT_NEAR(view.rangeAt(0.0), 3.0, 0.05);
  EXPECT_LT(view.rangeAt(M_PI / 2), 0.0);  // nothing seen there: unknown, not free
  EXPECT_LT(view.rangeAt(M_PI), 0.0);
  EXPECT_LT(RangeView().rangeAt(0.0), 0.0);
}

}  // namespace
}  // namespace contour_reg
