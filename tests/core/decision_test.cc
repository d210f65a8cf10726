#include <algorithm>
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "contour_reg/core/registration.h"
#include "contour_reg/core/transform_estimation.h"
#include "contour_reg/simulation/office.h"
#include "decision/checks.h"
#include "scenes.h"

namespace contour_reg {
namespace {

ContourFeatures featuresFrom(const simulation::World &world, const Eigen::Isometry2d &pose, unsigned seed) {
  return extractContourFeatures(test::scanFrom(world, pose, 0.01, seed), ContourParams{});
}

RegistrationResult registerPair(const simulation::World &world, const Eigen::Isometry2d &target_pose,
                                const Eigen::Isometry2d &source_pose, const RegistrationParams &params = {},
                                const simulation::World *source_world = nullptr, const decision::Checks &checks = {}) {
  const ContourFeatures target = featuresFrom(world, target_pose, 1);
  const ContourFeatures source = featuresFrom(source_world ? *source_world : world, source_pose, 2);
  std::mt19937 rng(3);
  return decision::registerContoursWith(source, target, params, checks, rng);
}

Eigen::Vector3d errorOf(const RegistrationResult &r, const Eigen::Isometry2d &target_pose,
                        const Eigen::Isometry2d &source_pose) {
  const Eigen::Isometry2d m = target_pose.inverse() * source_pose;
  return Eigen::Vector3d(r.transform(0, 2) - m.translation().x(), r.transform(1, 2) - m.translation().y(),
                         std::remainder(yawOf(r.transform) - std::atan2(m.linear()(1, 0), m.linear()(0, 0)), 2 * M_PI));
}

RegistrationParams withoutFreeSpace() {
  RegistrationParams params;
  params.free_space.enabled = false;
  return params;
}

RegistrationParams withoutContourHypotheses() {
  RegistrationParams params;
  params.local_fallback_min_overlap = 0.0;  // the corners' verdict stands
  return params;
}

// The source scan is 3 m ahead of the target along a corridor with a door every 3 m: one door
// back, the identity, puts walls on walls and doors on doors as well as the truth does.
TEST(Decision, FreeSpaceRefutesTheAliasOneDoorBack) {
  const simulation::World corridor = test::corridorOfDoors();
  const Eigen::Isometry2d target = test::pose2d(0, 0, 0), source = test::pose2d(3.0, 0.05, 1);

  const RegistrationResult with = registerPair(corridor, target, source);
  ASSERT_TRUE(with.converged) << with.reason;
  EXPECT_LT(errorOf(with, target, source).head<2>().norm(), 0.05);

  // Without the free-space term the contours cannot tell the truth from the identity, whose
  // source end wall, 6 m ahead, lies where the target saw 9 m of free space.
  const RegistrationResult without = registerPair(corridor, target, source, withoutFreeSpace());
  EXPECT_FALSE(without.converged);
  EXPECT_EQ(without.status, RegistrationStatus::kAmbiguous) << without.reason;
}

// The source scan is 5.1 m ahead along a corridor with a tooth every 1.4 m: the corners agree
// on a motion three teeth back, which puts the source's end wall where the target saw 9 m of
// free space. That contradiction sends the motion against the contours' own hypotheses.
TEST(Decision, ACornerMotionTheFreeSpaceContradictsMeetsTheContoursHypotheses) {
  const simulation::World corridor = test::sawtoothCorridor();
  const Eigen::Isometry2d target = test::pose2d(0, 0, 0), source = test::pose2d(5.1, 0.1, 0);

  const RegistrationResult r = registerPair(corridor, target, source);
  ASSERT_TRUE(r.converged) << r.reason;
  EXPECT_LT(errorOf(r, target, source).head<2>().norm(), 0.05);

  // Without the free-space term nothing tells the corners' motion, three teeth back, from the truth.
  const RegistrationResult without = registerPair(corridor, target, source, withoutFreeSpace());
  ASSERT_TRUE(without.converged) << without.reason;
  EXPECT_NEAR(errorOf(without, target, source).head<2>().norm(), 4.2, 0.1);

  // 5.7 m ahead, the contours' best rival fits as well as the corners' motion: no answer.
  const Eigen::Isometry2d farther = test::pose2d(5.7, 0.1, 0);
  const RegistrationResult tie = registerPair(corridor, target, farther);
  EXPECT_FALSE(tie.converged);
  EXPECT_EQ(tie.status, RegistrationStatus::kAmbiguous) << tie.reason;
}

TEST(Decision, PeopleWalkingThroughDoNotRefuteTheRightMotion) {
  const simulation::World room = simulation::makeFurnishedRoom();
  simulation::World with_people = room;  // two people in the source scan only
  with_people.addCircle({0.9, -0.2}, 0.2);
  with_people.addCircle({-0.5, 0.8}, 0.2);
  const Eigen::Isometry2d target = test::pose2d(0.0, -0.4, 10), source = test::pose2d(0.3, -0.3, 14);

  const RegistrationResult r = registerPair(room, target, source, {}, &with_people);
  ASSERT_TRUE(r.converged) << r.reason;
  EXPECT_LT(errorOf(r, target, source).head<2>().norm(), 0.02);
  EXPECT_LT(std::abs(errorOf(r, target, source).z()), 0.01);
  // The people are smaller than a moved object may be (FreeSpaceParams::min_object_length):
  // the score counts none of them against the motion.
  EXPECT_DOUBLE_EQ(r.score, r.overlap);
}

// A 6 m partition stands in the source scan only, where the target saw across the room: the
// right motion puts a tenth of the contours in the target's free space, but the source sees
// through none of the target's contour. What one scan alone has does not refute a motion.
TEST(Decision, AnObjectInOneScanOnlyDoesNotRefuteTheRightMotion) {
  const simulation::World room = simulation::makeFurnishedRoom();
  simulation::World partitioned = room;
  partitioned.addBox({-3.0, -1.0}, {3.0, -0.9});
  const Eigen::Isometry2d target = test::pose2d(0.0, 0.4, 10), source = test::pose2d(0.3, 0.5, 14);

  const RegistrationResult r = registerPair(room, target, source, {}, &partitioned);
  ASSERT_TRUE(r.converged) << r.reason;
  EXPECT_LT(errorOf(r, target, source).head<2>().norm(), 0.02);
  // Its score, the overlap less the share of both contours in the other scan's free space,
  // counts the partition: a tenth of the contours.
  EXPECT_NEAR(r.overlap - r.score, 0.1, 0.03);
  // The same where the contours' own motion is judged, the corners never deciding.
  RegistrationParams contours_only;
  contours_only.min_inliers = 1000;
  const RegistrationResult fallback = registerPair(room, target, source, contours_only, &partitioned);
  ASSERT_TRUE(fallback.converged && fallback.from_local_fallback) << fallback.reason;
  EXPECT_LT(errorOf(fallback, target, source).head<2>().norm(), 0.02);
  EXPECT_NEAR(fallback.overlap - fallback.score, 0.1, 0.03);
}

// The partition stands across the room in the target scan and 1 m in front of a wall in the source:
// each scan saw through the other's partition, over a tenth of the contours. The judge says
// the scans contradict the best motion rather than return it; without the free-space term it
// is returned.
TEST(Decision, AMotionBothScansContradictIsDeclined) {
  const simulation::World room = simulation::makeFurnishedRoom();
  simulation::World before = room, after = room;
  before.addBox({-3.0, -1.0}, {3.0, -0.9});
  after.addBox({-1.5, 4.0}, {4.5, 4.1});
  const Eigen::Isometry2d target = test::pose2d(0.0, 0.4, 10), source = test::pose2d(0.3, 0.5, 14);

  const RegistrationResult r = registerPair(before, target, source, {}, &after);
  EXPECT_FALSE(r.converged);
  EXPECT_EQ(r.status, RegistrationStatus::kContradicted) << r.reason;

  const RegistrationResult without = registerPair(before, target, source, withoutFreeSpace(), &after);
  ASSERT_TRUE(without.converged) << without.reason;
  EXPECT_LT(errorOf(without, target, source).head<2>().norm(), 0.02);
}

// Where the contours support their own motion only weakly (an overlap under local_fallback_min_overlap
// but at least beam_agreed_overlap_share of it), it stands when the beams of both scans agree with it. Chairs
// stand in the target scan only, where the source looks through empty space: their legs are
// returns, too short to be contour, and the weak motion is declined for its low overlap; the
// same motion supported well stands despite them. Without free space the weak motion is declined.
TEST(Decision, AWeaklySupportedMotionStandsOnlyWhereTheBeamsAgree) {
  const simulation::World room = simulation::makeFurnishedRoom();
  simulation::World chairs = room;
  for (double x = -4.5; x < 6.0; x += 1.5)  // three rows of chairs, four legs each
    for (const double y : {-2.5, 1.5, 3.5})
      for (const Eigen::Vector2d &leg : {Eigen::Vector2d(-0.2, -0.2), Eigen::Vector2d(-0.2, 0.2),
                                         Eigen::Vector2d(0.2, -0.2), Eigen::Vector2d(0.2, 0.2)})
        chairs.addCircle(Eigen::Vector2d(x, y) + leg, 0.025);
  const Eigen::Isometry2d target = test::pose2d(0.0, -0.4, 10), source = test::pose2d(0.3, -0.3, 14);
  RegistrationParams params;
  params.min_inliers = 1000;  // the corners never decide: the contours' own motion is judged
  const RegistrationResult strong = registerPair(room, target, source, params);
  ASSERT_TRUE(strong.converged && strong.from_local_fallback) << strong.reason;
  const RegistrationResult strong_among_chairs = registerPair(chairs, target, source, params, &room);
  ASSERT_TRUE(strong_among_chairs.converged) << strong_among_chairs.reason;

  decision::Checks checks;  // the same overlap made weak
  params.local_fallback_min_overlap = std::min(1.0, strong.overlap + 0.05);
  checks.beam_agreed_overlap_share = (strong.overlap - 0.1) / params.local_fallback_min_overlap;
  ASSERT_TRUE(params.validate() && checks.validate());
  const RegistrationResult weak = registerPair(room, target, source, params, nullptr, checks);
  ASSERT_TRUE(weak.converged) << weak.reason;
  EXPECT_LT(errorOf(weak, target, source).head<2>().norm(), 0.02);

  const RegistrationResult weak_among_chairs = registerPair(chairs, target, source, params, &room, checks);
  EXPECT_FALSE(weak_among_chairs.converged) << weak_among_chairs.reason;
  EXPECT_EQ(weak_among_chairs.status, RegistrationStatus::kLowOverlap) << weak_among_chairs.reason;
  EXPECT_NE(weak_among_chairs.reason.find("returns lie in the other's free space"), std::string::npos)
      << weak_among_chairs.reason;

  RegistrationParams without = params;
  without.free_space.enabled = false;
  const RegistrationResult weak_without = registerPair(room, target, source, without, nullptr, checks);
  EXPECT_FALSE(weak_without.converged);
  EXPECT_EQ(weak_without.status, RegistrationStatus::kLowOverlap) << weak_without.reason;
}

// A square room seen from its centre, turned 45 deg: turned -45 deg, the scan fits as well.
TEST(Decision, ARivalThatScoresAsWellIsAmbiguous) {
  simulation::World square;
  square.addPolygon({{-3, -3}, {3, -3}, {3, 3}, {-3, 3}});
  const Eigen::Isometry2d target = test::pose2d(0, 0, 0);

  const RegistrationResult turned = registerPair(square, target, test::pose2d(0, 0, 45));
  EXPECT_FALSE(turned.converged);
  EXPECT_EQ(turned.status, RegistrationStatus::kAmbiguous) << turned.reason;
  EXPECT_TRUE(turned.transform.isIdentity());

  // Turned 30 deg, the rival (-60 deg) leaves a sixth of the contour unpaired: no tie.
  const Eigen::Isometry2d less = test::pose2d(0, 0, 30);
  const RegistrationResult decided = registerPair(square, target, less);
  ASSERT_TRUE(decided.converged) << decided.reason;
  EXPECT_LT(errorOf(decided, target, less).norm(), 0.01);
}

// A LIDAR of 181 beams over 180 deg (SICK LMS200-like) in a corner of the office, 2 m along a
// wall and turned 31 deg: one corner and its two walls, seen from elsewhere, fit a motion
// 90 deg off (3.7 m from the truth) better than the truth by about the tie, for much of what
// the source sees lies outside the target's half view. The contours' free space, in stretches,
// barely tells them apart; the beams of both scans do: the alias puts a quarter of the returns
// where the other scan saw through, the truth almost none.
TEST(Decision, TheBeamsDecideBetweenMotionsThatFitNearlyAsWell) {
  const simulation::World office = simulation::makeOfficeWorld();
  const Eigen::Isometry2d target_pose = test::pose2d(15.3, 3.3, -90.0), source_pose = test::pose2d(15.3, 1.3, -121.04);
  const auto registerWith = [&](const RegistrationParams &params) {
    std::mt19937 rng(1);
    const simulation::LidarModel sick = simulation::LidarModel::sickLms200();
    const ContourFeatures target = extractContourFeatures(simulation::simulateScan(office, target_pose, sick, rng), {});
    const ContourFeatures source = extractContourFeatures(simulation::simulateScan(office, source_pose, sick, rng), {});
    std::mt19937 ransac(3);
    return decision::registerContoursWith(source, target, params, {}, ransac);
  };
  const RegistrationResult r = registerWith({});
  EXPECT_FALSE(r.converged);
  EXPECT_EQ(r.status, RegistrationStatus::kAmbiguous) << r.reason;
  // It names both motions: the alias and the truth, which a prediction can choose between.
  ASSERT_EQ(r.alternatives.size(), 2u) << r.reason;
  const Eigen::Isometry2d truth = target_pose.inverse() * source_pose;
  const auto off = [&](const RejectedMotion &m) {
    return (m.transform.topRightCorner<2, 1>() - truth.translation()).norm();
  };
  EXPECT_GT(off(r.alternatives[0]), 3.0);
  EXPECT_LT(off(r.alternatives[1]), 0.1);

  // Without the free space's evidence the alias stands.
  const RegistrationResult without = registerWith(withoutFreeSpace());
  ASSERT_TRUE(without.converged) << without.reason;
  EXPECT_GT(errorOf(without, target_pose, source_pose).head<2>().norm(), 3.0);
}

// The result names the best motion the judge weighed and did not return, for pictures and
// diagnosis: the rival of a converged answer, the motion of a declined one.
TEST(Decision, TheResultNamesTheBestRejectedMotion) {
  const simulation::World corridor = test::corridorOfDoors();
  const Eigen::Isometry2d target = test::pose2d(0, 0, 0), source = test::pose2d(3.0, 0.05, 1);
  const RegistrationResult right = registerPair(corridor, target, source);
  ASSERT_TRUE(right.converged) << right.reason;
  ASSERT_TRUE(right.rejected.has_value());
  // One door back (no motion): the contours fit it, the free space refutes it.
  EXPECT_LT((right.rejected->transform.topRightCorner<2, 1>()).norm(), 0.1);
  EXPECT_GT(right.rejected->overlap, right.overlap - 0.05);
  EXPECT_GT(right.rejected->overlap - right.rejected->score, 0.03);
  EXPECT_LT(right.rejected->score, right.overlap - 0.05);
  // The scores the judge compared: the answer's beats the rival's by more than the tie.
  EXPECT_GT(right.score, right.rejected->score + 0.05);

  simulation::World square;
  square.addPolygon({{-3, -3}, {3, -3}, {3, 3}, {-3, 3}});
  const RegistrationResult tie = registerPair(square, target, test::pose2d(0, 0, 45));
  ASSERT_FALSE(tie.converged);
  ASSERT_TRUE(tie.rejected.has_value());
  // The declined motion is one of the two turns that fit: 45 deg, or -45 deg.
  EXPECT_NEAR(std::abs(yawOf(tie.rejected->transform)), M_PI / 4, 0.02);
  EXPECT_GT(tie.rejected->overlap, 0.8);

  // A corner motion declined for its overlap alone, with the contours' hypotheses off, is
  // scored all the same.
  const simulation::World room = simulation::makeFurnishedRoom();
  decision::Checks strict;
  strict.corner_min_overlap = strict.two_inlier_min_overlap = 0.999;
  const RegistrationResult declined = registerPair(room, test::pose2d(0, 0, 10), test::pose2d(0.3, 0.1, 12),
                                                   withoutContourHypotheses(), nullptr, strict);
  ASSERT_FALSE(declined.converged);
  ASSERT_TRUE(declined.rejected.has_value());
  EXPECT_GT(declined.rejected->overlap, 0.5);
  EXPECT_NEAR(declined.rejected->score, declined.rejected->overlap, 0.05);  // the right motion: no free space
}

// An ambiguous verdict names the distinct motions that fit as well, each with its covariance,
// so that a prior on the motion can decide between them: the square turned 45 deg fits a turn
// of 45 deg and one of -45 deg; the row of doors without the free-space term, the truth (3 m
// ahead) and one door back (no motion).
TEST(Decision, AnAmbiguousVerdictNamesTheMotionsThatFitAsWell) {
  simulation::World square;
  square.addPolygon({{-3, -3}, {3, -3}, {3, 3}, {-3, 3}});
  const RegistrationResult tie = registerPair(square, test::pose2d(0, 0, 0), test::pose2d(0, 0, 45));
  ASSERT_EQ(tie.status, RegistrationStatus::kAmbiguous) << tie.reason;
  ASSERT_EQ(tie.alternatives.size(), 2u);
  EXPECT_NEAR(yawOf(tie.alternatives[0].transform) * yawOf(tie.alternatives[1].transform), -M_PI * M_PI / 16, 0.03);
  for (const RejectedMotion &motion : tie.alternatives) {
    EXPECT_NEAR(std::abs(yawOf(motion.transform)), M_PI / 4, 0.02);
    EXPECT_GT(motion.covariance(2, 2), 0.0);
    EXPECT_LT(motion.covariance(2, 2), std::pow(1.0 * M_PI / 180.0, 2));  // the turn's 2 % of 45 deg and little more
  }

  const simulation::World corridor = test::corridorOfDoors();
  const RegistrationResult doors =
      registerPair(corridor, test::pose2d(0, 0, 0), test::pose2d(3.0, 0.05, 1), withoutFreeSpace());
  ASSERT_EQ(doors.status, RegistrationStatus::kAmbiguous) << doors.reason;
  ASSERT_EQ(doors.alternatives.size(), 2u);
  double ahead = doors.alternatives[0].transform(0, 2), behind = doors.alternatives[1].transform(0, 2);
  if (ahead < behind) std::swap(ahead, behind);
  EXPECT_NEAR(ahead, 3.0, 0.05);
  EXPECT_NEAR(behind, 0.0, 0.05);

  // Every other verdict leaves them empty.
  const RegistrationResult decided = registerPair(square, test::pose2d(0, 0, 0), test::pose2d(0, 0, 30));
  ASSERT_TRUE(decided.converged) << decided.reason;
  EXPECT_TRUE(decided.alternatives.empty());
}

// The square turned 30 deg: two corners, the refinement pairs 89 % of the contour.
TEST(Decision, TwoCornersStandOnlyWithALargeOverlap) {
  simulation::World square;
  square.addPolygon({{-3, -3}, {3, -3}, {3, 3}, {-3, 3}});
  const Eigen::Isometry2d target = test::pose2d(0, 0, 0), source = test::pose2d(0, 0, 30);

  const RegistrationResult two = registerPair(square, target, source, withoutContourHypotheses());
  ASSERT_TRUE(two.converged) << two.reason;
  EXPECT_FALSE(two.from_local_fallback);

  decision::Checks strict;
  strict.two_inlier_min_overlap = 0.95;
  const RegistrationResult declined = registerPair(square, target, source, withoutContourHypotheses(), nullptr, strict);
  EXPECT_FALSE(declined.converged);
  EXPECT_EQ(declined.status, RegistrationStatus::kLowOverlap) << declined.reason;
  EXPECT_NE(declined.reason.find("overlap only 8"), std::string::npos) << declined.reason;
}

// With the contours' own hypotheses off, a motion the corners agree on and the judge declines
// keeps the judge's verdict as its status: the partition each scan saw through is
// `contradicted`, the square turned 45 deg `ambiguous` with both turns named.
TEST(Decision, TheCornersDeclinedMotionNamesTheJudgesVerdict) {
  const simulation::World room = simulation::makeFurnishedRoom();
  simulation::World before = room, after = room;
  before.addBox({-3.0, -1.0}, {3.0, -0.9});
  after.addBox({-1.5, 4.0}, {4.5, 4.1});
  const RegistrationResult seen_through =
      registerPair(before, test::pose2d(0.0, 0.4, 10), test::pose2d(0.3, 0.5, 14), withoutContourHypotheses(), &after);
  EXPECT_FALSE(seen_through.converged);
  EXPECT_EQ(seen_through.status, RegistrationStatus::kContradicted) << seen_through.reason;
  EXPECT_TRUE(seen_through.alternatives.empty());

  simulation::World square;
  square.addPolygon({{-3, -3}, {3, -3}, {3, 3}, {-3, 3}});
  const RegistrationResult turned =
      registerPair(square, test::pose2d(0, 0, 0), test::pose2d(0, 0, 45), withoutContourHypotheses());
  EXPECT_FALSE(turned.converged);
  EXPECT_EQ(turned.status, RegistrationStatus::kAmbiguous) << turned.reason;
  ASSERT_EQ(turned.alternatives.size(), 2u) << turned.reason;
  for (const RejectedMotion &motion : turned.alternatives)
    EXPECT_NEAR(std::abs(yawOf(motion.transform)), M_PI / 4, 0.02);
}

TEST(Decision, InliersCloserThanTheirMinimumSpreadAreDegenerate) {
  const simulation::World room = simulation::makeFurnishedRoom();
  decision::Checks checks;
  checks.min_inlier_spread = 100.0;  // m, more than any two corners of the room lie apart
  const RegistrationResult r = registerPair(room, test::pose2d(0, 0, 10), test::pose2d(0.3, 0.1, 12),
                                            withoutContourHypotheses(), nullptr, checks);
  EXPECT_FALSE(r.converged);
  EXPECT_EQ(r.status, RegistrationStatus::kDegenerate) << r.reason;
}

// A LIDAR of 3 m range and 180 deg field of view in a bare corridor, the source 0.35 m
// further along it: each scan's walls end where its range ends and where its field of view
// begins, ends that move with the sensor. At no motion they coincide, and the overlap is
// largest there; moved along the corridor, the source's walls reach past the target's view,
// where the target saw nothing to disagree. The probes of the weakest direction decide alone
// (the Hessian's degeneracy test off): such ends pin no motion.
TEST(Decision, TheEndsOfTheViewPinNoMotion) {
  const simulation::World corridor = test::bareCorridor(30.0);
  simulation::LidarModel short_range = simulation::LidarModel::sickLms200();
  short_range.range_max = 3.0;
  decision::Checks checks;
  checks.refinement_model.degeneracy_ratio = 0.0;
  for (unsigned seed = 1; seed <= 4; ++seed) {
    std::mt19937 rng_a(seed), rng_b(seed + 100), rng(3);
    const ContourFeatures target = extractContourFeatures(
        simulation::simulateScan(corridor, test::pose2d(0, 0, 0), short_range, rng_a), ContourParams{});
    const ContourFeatures source = extractContourFeatures(
        simulation::simulateScan(corridor, test::pose2d(0.35, 0.02, 1), short_range, rng_b), ContourParams{});
    const RegistrationResult r = decision::registerContoursWith(source, target, {}, checks, rng);
    EXPECT_FALSE(r.converged) << "seed " << seed << ": x " << r.transform(0, 2) << " m, truth 0.35 m";
    EXPECT_EQ(r.status, RegistrationStatus::kUnconstrained) << "seed " << seed << ": " << r.reason;
  }
}

// The corridor and the circle, whose direction stays free, are in registration_test.cc.

}  // namespace
}  // namespace contour_reg
