// Motion hypotheses from the contours' direction and wall-offset histograms, the local
// fallback that refines them when the corners cannot decide, and the probe along the weakest
// direction that both the fallback and motions of few corners must pass.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "contour_reg/core/direction_histogram.h"
#include "contour_reg/core/refinement.h"
#include "contour_reg/core/registration.h"
#include "contour_reg/core/transform_estimation.h"
#include "contour_reg/simulation/office.h"
#include "contour_reg/simulation/simulated_run.h"
#include "decision/checks.h"
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
  decision::Checks checks;
  checks.direction_hypotheses = direction_hypotheses;
  std::mt19937 rng(5);
  return decision::registerContoursWith(source, target, params, checks, rng);
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

// A corridor 2.5 m wide, open behind the sensor, and ahead at `end` m either closed or
// ending in a stub of `stub` m on one wall.
simulation::World corridorEndingIn(double end, double stub) {
  simulation::World corridor;
  corridor.addSegment({-12.0, 1.3}, {end, 1.3});
  corridor.addSegment({-12.0, -1.2}, {end, -1.2});
  corridor.addSegment({end, -1.2}, {end, -1.2 + stub});
  return corridor;
}

constexpr double kAlongTheAxis[] = {0.05, 0.1, 0.15, 0.2, 0.3, 0.4, 0.5};  // m

TEST(LocalFallback, CorridorWithAClosedEndPassesTheProbes) {
  const simulation::World corridor = corridorEndingIn(10.0, 2.5);
  const ContourFeatures target = featuresFrom(corridor, test::pose2d(0, 0, 0), 8);
  for (double along : kAlongTheAxis) {
    SCOPED_TRACE(testing::Message() << along << " m along the corridor");
    const Eigen::Isometry2d motion = test::pose2d(along, 0.05, 2);
    const RegistrationResult r = registerWithoutCorners(featuresFrom(corridor, motion, 9), target, true);
    ASSERT_TRUE(r.converged) << r.reason;
    EXPECT_TRUE(r.from_local_fallback);
    EXPECT_NEAR(r.transform(0, 2), along, 0.03);
    EXPECT_NEAR(r.transform(1, 2), 0.05, 0.03);
    EXPECT_NEAR(yawOf(r.transform), 2.0 * kDeg, 0.5 * kDeg);
  }
}

TEST(LocalFallback, CorridorWhoseAxisOnlyAStubConstrainsFailsTheProbes) {
  // The end wall is a 0.2 m stub: moving along the axis barely changes the fit.
  const simulation::World corridor = corridorEndingIn(6.0, 0.2);
  const ContourFeatures target = featuresFrom(corridor, test::pose2d(0, 0, 0), 8);
  RegistrationParams without_probe;
  without_probe.min_special_points = 1 << 20;
  without_probe.probe_distance = 0.0;
  // The free space's check for repeated structure finds the motion along the axis too: off.
  without_probe.free_space.enabled = false;
  int wrong_without_probe = 0;
  for (double along : kAlongTheAxis) {
    SCOPED_TRACE(testing::Message() << along << " m along the corridor");
    const ContourFeatures source = featuresFrom(corridor, test::pose2d(along, 0.05, 2), 9);
    const RegistrationResult r = registerWithoutCorners(source, target, true);
    EXPECT_FALSE(r.converged) << r.transform;
    EXPECT_NE(r.reason.find("weakly constrained"), std::string::npos) << r.reason;
    std::mt19937 rng(5);
    const RegistrationResult unchecked = registerContours(source, target, without_probe, rng);
    if (unchecked.converged && std::abs(unchecked.transform(0, 2) - along) > 0.1) ++wrong_without_probe;
  }
  // Without the probes the fallback claims a wrong position along the axis.
  EXPECT_GT(wrong_without_probe, 0);
}

// A corridor with a door recess (`depth` deep, `door` wide) every `period` m along one wall.
simulation::World corridorWithRecesses(double depth, double door, double period) {
  simulation::World corridor;
  corridor.addSegment({-15.0, 1.3}, {15.0, 1.3});
  for (double x = -15.0; x < 15.0; x += period) {
    corridor.addSegment({x, -1.2}, {x + period - door, -1.2});
    corridor.addSegment({x + period - door, -1.2}, {x + period - door, -1.2 - depth});
    corridor.addSegment({x + period - door, -1.2 - depth}, {x + period, -1.2 - depth});
    corridor.addSegment({x + period, -1.2 - depth}, {x + period, -1.2});
  }
  return corridor;
}

// The settings and the judge's checks (decision/checks.h) a test registers with.
struct Settings {
  RegistrationParams params;
  decision::Checks checks;
};

// Without the checks of motions of few corners.
Settings withoutCornerChecks() {
  Settings settings;
  settings.checks.probe_max_inliers = 0;
  settings.checks.guess_check_max_inliers = 0;
  settings.checks.corner_min_overlap = 0.0;
  return settings;
}

RegistrationResult registerSeeded(const ContourFeatures &source, const ContourFeatures &target,
                                  const Settings &settings) {
  std::mt19937 rng(5);
  return decision::registerContoursWith(source, target, settings.params, settings.checks, rng);
}

RegistrationResult registerSeeded(const ContourFeatures &source, const ContourFeatures &target,
                                  const RegistrationParams &params) {
  return registerSeeded(source, target, Settings{params, decision::Checks{}});
}

TEST(CornerProbe, AMotionOfThreeCornersTheContoursLeaveFlatIsDeclined) {
  // Recesses 0.25 m deep every 4 m, 2 cm range noise, seen from 0.8 m further on: three noisy
  // door corners agree on a wrong motion, where the shallow recesses leave the axis flat and
  // little of the contours overlaps.
  const simulation::World corridor = corridorWithRecesses(0.25, 0.6, 4.0);
  const ContourFeatures target = featuresFrom(corridor, test::pose2d(0, 0, 0), 8, 0.02);
  const ContourFeatures source = featuresFrom(corridor, test::pose2d(0.8, 0.05, 2), 9, 0.02);
  Settings unrefined = withoutCornerChecks();  // the corners' motion, unjudged
  unrefined.params.refinement.enabled = false;
  const RegistrationResult corners_alone = registerSeeded(source, target, unrefined);
  ASSERT_TRUE(corners_alone.converged) << corners_alone.reason;
  ASSERT_EQ(corners_alone.inliers.size(), 3u);
  EXPECT_GT(std::abs(corners_alone.transform(0, 2) - 0.8), 0.5);  // confidently wrong

  // The contours' hypotheses alone: the motion puts little of the contour on the target.
  const RegistrationResult by_hypotheses = registerSeeded(source, target, withoutCornerChecks());
  EXPECT_FALSE(by_hypotheses.converged) << by_hypotheses.transform;
  EXPECT_NE(by_hypotheses.reason.find("3 special points, but they put only"), std::string::npos)
      << by_hypotheses.reason;

  Settings probed = withoutCornerChecks();  // the probe alone
  probed.checks.probe_max_inliers = 3;
  const RegistrationResult by_probe = registerSeeded(source, target, probed);
  EXPECT_FALSE(by_probe.converged) << by_probe.transform;
  EXPECT_NE(by_probe.reason.find("3 special points, and the contours leave a direction weakly constrained"),
            std::string::npos)
      << by_probe.reason;

  Settings overlapping = withoutCornerChecks();  // the overlap alone
  overlapping.checks.corner_min_overlap = 0.3;
  const RegistrationResult by_overlap = registerSeeded(source, target, overlapping);
  EXPECT_FALSE(by_overlap.converged) << by_overlap.transform;
  EXPECT_NE(by_overlap.reason.find("3 special points agree, but the contours overlap only"), std::string::npos)
      << by_overlap.reason;

  EXPECT_FALSE(registerSeeded(source, target, RegistrationParams{}).converged);

  // Without the local fallback after them, each decline keeps the verdict of the check that
  // made it: a distinct motion fits as well, a direction is left free, too little overlaps.
  for (Settings *settings : {&probed, &overlapping}) settings->params.local_fallback_min_overlap = 0.0;
  Settings hypotheses_alone = withoutCornerChecks();
  hypotheses_alone.params.local_fallback_min_overlap = 0.0;
  EXPECT_EQ(registerSeeded(source, target, hypotheses_alone).status, RegistrationStatus::kAmbiguous);
  EXPECT_EQ(registerSeeded(source, target, probed).status, RegistrationStatus::kUnconstrained);
  EXPECT_EQ(registerSeeded(source, target, overlapping).status, RegistrationStatus::kLowOverlap);
}

TEST(CornerProbe, AMotionOfThreeCornersOnePeriodOffAlongARowOfDoorsIsAmbiguous) {
  // Recesses 0.2 m deep every 3 m, seen from 0.5 m further on: three door corners match one
  // period off. Refined from the guess (none), the contours settle on the true motion, but it
  // and the motions a whole period off fit what both scans saw alike: no answer.
  const simulation::World corridor = corridorWithRecesses(0.2, 0.9, 3.0);
  const ContourFeatures target = featuresFrom(corridor, test::pose2d(0, 0, 0), 8);
  const ContourFeatures source = featuresFrom(corridor, test::pose2d(0.5, 0.05, 2), 9);
  Settings unjudged = withoutCornerChecks();  // the corners' motion, the free space not weighed
  unjudged.params.free_space.enabled = false;
  const RegistrationResult corners_alone = registerSeeded(source, target, unjudged);
  ASSERT_TRUE(corners_alone.converged) << corners_alone.reason;
  ASSERT_EQ(corners_alone.inliers.size(), 3u);
  EXPECT_NEAR(corners_alone.transform(0, 2), 0.5 - 3.0, 0.03);

  const RegistrationResult r = registerSeeded(source, target, RegistrationParams{});
  EXPECT_FALSE(r.converged) << r.transform;
  EXPECT_EQ(r.status, RegistrationStatus::kAmbiguous) << r.reason;
  EXPECT_NE(r.reason.find("a motion a period along repeated structure fits what both scans saw as well"),
            std::string::npos)
      << r.reason;
}

TEST(Repetition, TheEndOfARowOfDoorsTellsMotionsAPeriodApart) {
  // The same row of doors closed by a wall 4.5 m ahead: only the true motion puts that wall
  // where the target saw it.
  simulation::World corridor = corridorWithRecesses(0.2, 0.9, 3.0);
  corridor.addSegment({4.5, -1.4}, {4.5, 1.3});
  const ContourFeatures target = featuresFrom(corridor, test::pose2d(0, 0, 0), 8);
  for (double along : {0.5, 1.0, 2.0}) {
    SCOPED_TRACE(testing::Message() << along << " m along the corridor");
    const ContourFeatures source = featuresFrom(corridor, test::pose2d(along, 0.05, 2), 9);
    const RegistrationResult r = registerSeeded(source, target, RegistrationParams{});
    ASSERT_TRUE(r.converged) << r.reason;
    EXPECT_NEAR(r.transform(0, 2), along, 0.03);
    EXPECT_NEAR(r.transform(1, 2), 0.05, 0.03);
  }
}

TEST(Repetition, MotionsAPeriodApartAlongAnOpenRowOfDoorsAreAmbiguous) {
  // The row open at both ends: what the two scans saw does not tell the true motion from one a
  // whole period off. Without the free space, the contours answer anyway.
  const simulation::World corridor = corridorWithRecesses(0.2, 0.9, 3.0);
  const ContourFeatures target = featuresFrom(corridor, test::pose2d(0, 0, 0), 8);
  int converged_without_free_space = 0;
  for (double along : {1.0, 3.5}) {
    SCOPED_TRACE(testing::Message() << along << " m along the corridor");
    const ContourFeatures source = featuresFrom(corridor, test::pose2d(along, 0.05, 2), 9);
    const RegistrationResult r = registerSeeded(source, target, RegistrationParams{});
    EXPECT_FALSE(r.converged) << r.transform;
    EXPECT_EQ(r.status, RegistrationStatus::kAmbiguous) << r.reason;
    RegistrationParams without_free_space;
    without_free_space.free_space.enabled = false;
    converged_without_free_space += registerSeeded(source, target, without_free_space).converged;
  }
  EXPECT_GT(converged_without_free_space, 0);
}

TEST(Repetition, PairsAlongTheBuiltInDoorRowAreNotAnsweredAPeriodOff) {
  // The simulator's door row at 1 Hz and 1 m/s, as `simulate --map doors --path line` makes it:
  // pairs 2 and 4 m apart whose views of the corridor also fit a motion a whole period (3 m)
  // shorter. The beams meet the far walls at glancing angles, where the target's view between
  // two returns lies nearer than its contour: what both scans saw must still count as seen.
  simulation::RunSettings settings;
  settings.rate = 1.0;
  settings.speed = 1.0;
  const simulation::SimulatedRun run =
      simulation::simulateRun(simulation::makeBuiltInWorld("doors"), simulation::doorRowPath("line"), settings);
  for (const auto &[first, second] : {std::pair{1, 5}, std::pair{22, 26}, std::pair{26, 28}}) {
    SCOPED_TRACE(testing::Message() << "scans " << first << " and " << second);
    const ContourFeatures target = extractContourFeatures(run.log.entries[first].scan, ContourParams{});
    const ContourFeatures source = extractContourFeatures(run.log.entries[second].scan, ContourParams{});
    const RegistrationResult r = registerSeeded(source, target, RegistrationParams{});
    const double truth = second - first;  // m along the corridor
    if (r.converged) {
      EXPECT_NEAR(r.transform(0, 2), truth, 0.1) << "converged a period off";
    } else {
      EXPECT_TRUE(r.status == RegistrationStatus::kAmbiguous || r.status == RegistrationStatus::kUnconstrained)
          << r.reason;
    }
  }
}

TEST(Repetition, TheWallBetweenSparseReturnsIsWhatTheTargetSaw) {
  // The same door row seen by a SICK-like LIDAR (180 deg ahead, 1 deg beams; `simulate
  // --lidar sick`, seed 1): its beams meet the walls ahead at a glancing angle, their returns
  // 0.9 m apart at 8 m, too sparse for a contour beyond about 5 m. Scans 3 and 4 m apart also
  // fit a motion a whole period shorter,
  // which lays the source on the target's contours; the truth lays the source's far part on
  // the walls between the target's sparse returns. That is what the target saw: on the view
  // both share the two fit alike, and the pair is ambiguous, not answered a period off.
  simulation::RunSettings settings;
  settings.rate = 1.0;
  settings.speed = 1.0;
  settings.lidar = simulation::LidarModel::sickLms200();
  settings.lidar.range_max = 40.0;  // read as the command line reads it: the row's far end unseen
  const simulation::SimulatedRun run =
      simulation::simulateRun(simulation::makeBuiltInWorld("doors"), simulation::doorRowPath("line"), settings);
  for (const auto &[first, second] : {std::pair{17, 20}, std::pair{3, 7}}) {
    SCOPED_TRACE(testing::Message() << "scans " << first << " and " << second);
    const ContourFeatures target = extractContourFeatures(run.log.entries[first].scan, ContourParams{});
    const ContourFeatures source = extractContourFeatures(run.log.entries[second].scan, ContourParams{});
    const RegistrationResult r = registerSeeded(source, target, RegistrationParams{});
    EXPECT_EQ(r.status, RegistrationStatus::kAmbiguous)
        << r.reason << "; answered " << r.transform(0, 2) << " m, truth " << second - first << " m";
  }
}

// Shallow recesses 1.5 m wide every 5 m along one wall: along the corridor little pulls a
// refinement, which slides a few centimetres an iteration. Scans from x0 and from dx, dy further.
struct ShallowRecessPair {
  ContourFeatures target, source;
  ShallowRecessPair(double x0, double dx, double dy, double yaw_deg) {
    const simulation::World corridor = corridorWithRecesses(0.1, 1.5, 5.0);
    target = featuresFrom(corridor, test::pose2d(x0, 0, 0), 8);
    source = featuresFrom(corridor, test::pose2d(x0 + dx, dy, yaw_deg), 9);
  }
};

TEST(LocalFallback, TheBestGivesWayToAClearlyBetterMotionAProbeFound) {
  // Seen 0.4 m apart: the corners cannot decide, and the refinement of the contours' best
  // hypothesis stops near no motion. A probe along the corridor settles on the true motion,
  // which puts clearly more of the contour on the target: the judge takes it.
  const ShallowRecessPair pair(0.0, 0.4, 0.05, 2);
  const RegistrationResult r = registerSeeded(pair.source, pair.target, RegistrationParams{});
  ASSERT_TRUE(r.converged) << r.reason;
  EXPECT_TRUE(r.from_local_fallback);
  EXPECT_NEAR(r.transform(0, 2), 0.4, 0.03);
  EXPECT_NEAR(r.transform(1, 2), 0.05, 0.03);
  ASSERT_TRUE(r.rejected.has_value());  // the hypothesis it gave way to
  EXPECT_LT(r.rejected->transform(0, 2), 0.2);
}

// Seen 0.3 m apart, the refinement from no motion slides. Cut short by the iterations it says
// so, and refined on from where it stopped it arrives.
TEST(Refinement, ASlideAlongACorridorCutShortIsFlaggedAndArrivesWhenRefinedOn) {
  const ShallowRecessPair pair(2.0, 0.3, 0.0, 0);
  const ContourRefiner refiner(pair.target, RefinementParams{});
  const std::vector<Eigen::Vector2d> samples = contourSamples(pair.source, RefinementModel{}.sample_step);
  const RefinementResult cut = refiner.refine(samples, Eigen::Matrix3d::Identity(), RefinementParams{});
  EXPECT_EQ(cut.iterations, RefinementParams{}.max_iterations);
  EXPECT_TRUE(cut.sliding);
  EXPECT_GT(std::abs(cut.transform(0, 2) - 0.3), 0.05);
  RefinementParams on;
  on.max_distance = on.min_distance;
  const RefinementResult arrived = refiner.refine(samples, cut.transform, on);
  EXPECT_FALSE(arrived.sliding);
  EXPECT_NEAR(arrived.transform(0, 2), 0.3, 0.01);
  EXPECT_NEAR(arrived.transform(1, 2), 0.0, 0.01);
}

// The same pair registered: the contours' hypotheses that slid are refined on, and the motion
// is found rather than declined as unconstrained.
TEST(LocalFallback, AHypothesisStillSlidingIsRefinedOnToTheMotion) {
  const ShallowRecessPair pair(2.0, 0.3, 0.0, 0);
  const RegistrationResult r = registerSeeded(pair.source, pair.target, RegistrationParams{});
  ASSERT_TRUE(r.converged) << r.reason;
  EXPECT_NEAR(r.transform(0, 2), 0.3, 0.01);
  EXPECT_NEAR(r.transform(1, 2), 0.0, 0.01);
}

}  // namespace
}  // namespace contour_reg
