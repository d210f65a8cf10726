// The point-to-line refinement on the contours: it pairs with the target's equalized
// vertices, so sparse beams still pair, and it pulls a nearby start onto the true motion.
#include <cmath>
#include <random>

#include <gtest/gtest.h>
#include <Eigen/Eigenvalues>

#include "contour_reg/core/contour_features.h"
#include "contour_reg/core/equalization.h"
#include "contour_reg/core/refinement.h"
#include "contour_reg/core/transform_estimation.h"
#include "scenes.h"

namespace contour_reg {
namespace {

// A 180-beam LIDAR over 180 deg (1 deg apart), as in older SICK logs: at 10 m its beams hit a
// wall 17 cm apart, more than the refinement's final pairing distance (8 cm).
simulation::LidarModel sparseLidar() {
  simulation::LidarModel model;
  model.beams = 181;
  model.field_of_view = M_PI;
  model.range_max = 30.0;
  model.range_noise = 0.01;
  return model;
}

ContourFeatures sparseFeatures(const simulation::World &world, const Eigen::Isometry2d &pose, unsigned seed) {
  std::mt19937 rng(seed);
  return extractContourFeatures(simulation::simulateScan(world, pose, sparseLidar(), rng), ContourParams{});
}

Eigen::Matrix3d matrixOf(const Eigen::Isometry2d &pose) { return pose.matrix(); }

// The source samples are centred on each contour's raw segment (equalizeCentred): a segment
// and the same segment run the other way give the same samples. Samples taken from the first
// point on leave the remainder at the same end of every contour of a scan, and registrations
// then turn their estimates a little one way: over a drive, a heading drift of one sign.
TEST(Refinement, SamplesDoNotDependOnTheDirectionOfTheContour) {
  const RefinementModel model;
  for (const double length : {1.05, 1.1, 1.13}) {  // 10 samples 0.1 m apart and 0.05, 0.1, 0.13 m left over
    ComplexSequence line;
    for (int n = 0; n <= 30; ++n) line.push_back({2.0 + length * n / 30.0, 1.0});
    ContourFeatures forward, backward;
    forward.segments = {ContourSegment{line, {}}};
    backward.segments = {ContourSegment{ComplexSequence(line.rbegin(), line.rend()), {}}};
    forward.contours = equalizeSegments(forward.segments, EqualizationParams{});
    backward.contours = equalizeSegments(backward.segments, EqualizationParams{});
    const std::vector<Eigen::Vector2d> a = contourSamples(forward, model.sample_step);
    const std::vector<Eigen::Vector2d> b = contourSamples(backward, model.sample_step);
    ASSERT_EQ(a.size(), b.size()) << length;
    ASSERT_GE(a.size(), 10u);
    for (std::size_t k = 0; k < a.size(); ++k)
      EXPECT_NEAR((a[k] - b[b.size() - 1 - k]).norm(), 0.0, 1e-9) << "length " << length << ", sample " << k;
    // Centred: as far from the line's start as the last sample is from its end.
    EXPECT_NEAR(a.front().x() - 2.0, 2.0 + length - a.back().x(), 1e-9) << length;
  }
}

TEST(Refinement, SparseBeamsOnDistantWallsPairAtTheTrueMotion) {
  simulation::World hall;  // 24 m x 16 m, the sensor at its middle: walls 8-12 m away
  hall.addBox({-12.0, -8.0}, {12.0, 8.0});
  hall.addBox({3.0, 2.0}, {4.0, 3.0});
  const Eigen::Isometry2d motion = test::pose2d(0.3, 0.1, 2);
  const ContourFeatures target = sparseFeatures(hall, test::pose2d(0, 0, 0), 1);
  const ContourFeatures source = sparseFeatures(hall, motion, 2);
  const RefinementResult r = refineOnContours(source, target, matrixOf(motion), RefinementParams{});
  // Samples that lie between two sparse raw points of the target still find their partner.
  EXPECT_GT(r.overlap, 0.9);
  EXPECT_NEAR(r.transform(0, 2), 0.3, 0.02);
  EXPECT_NEAR(r.transform(1, 2), 0.1, 0.02);
  EXPECT_NEAR(yawOf(r.transform), 2.0 * M_PI / 180.0, 0.2 * M_PI / 180.0);
}

// Two scans of the furnished room, the source moved by `motion` from the target.
struct RoomPair {
  const test::RoomWithBoxes room;
  const Eigen::Isometry2d motion = test::pose2d(0.4, -0.2, 5);
  const ContourFeatures target =
      extractContourFeatures(test::scanFrom(room.world, test::pose2d(0, 0, 0), 0.01, 3), ContourParams{});
  const ContourFeatures source = extractContourFeatures(test::scanFrom(room.world, motion, 0.01, 4), ContourParams{});
};

TEST(Refinement, PullsANearbyStartOntoTheTrueMotion) {
  const RoomPair pair;
  const RefinementResult r =
      refineOnContours(pair.source, pair.target, matrixOf(test::pose2d(0.5, -0.05, 7)), RefinementParams{});
  EXPECT_GT(r.overlap, 0.9);
  EXPECT_FALSE(r.degenerate);
  EXPECT_NEAR(r.transform(0, 2), 0.4, 0.01);
  EXPECT_NEAR(r.transform(1, 2), -0.2, 0.01);
  EXPECT_NEAR(yawOf(r.transform), 5.0 * M_PI / 180.0, 0.2 * M_PI / 180.0);
}

// A caller that only asks whether a start leads back to a known motion stops the refinement
// once it is there: fewer iterations, ending near that motion; a motion never reached changes
// nothing.
TEST(Refinement, StopsOnceItHasArrivedNearAGivenMotion) {
  const RoomPair pair;
  const ContourRefiner refiner(pair.target, RefinementParams{});
  const std::vector<Eigen::Vector2d> samples = contourSamples(pair.source, RefinementModel{}.sample_step);
  const Eigen::Matrix3d start = matrixOf(test::pose2d(0.55, -0.05, 8));
  const RefinementResult full = refiner.refine(samples, start, RefinementParams{});
  const auto near_truth = [&](const Eigen::Matrix3d &m) {
    return (m.topRightCorner<2, 1>() - matrixOf(pair.motion).topRightCorner<2, 1>()).norm() < 0.03;
  };
  const RefinementResult stopped = refiner.refine(samples, start, RefinementParams{}, near_truth);
  EXPECT_LT(stopped.iterations, full.iterations);
  EXPECT_TRUE(near_truth(stopped.transform));
  const RefinementResult never =
      refiner.refine(samples, start, RefinementParams{}, [](const Eigen::Matrix3d &) { return false; });
  EXPECT_EQ(never.iterations, full.iterations);
  EXPECT_TRUE(never.transform.isApprox(full.transform));
}

// The covariance's term for stretches of contour that disagree (correlation_length) changes
// neither the motion nor any direction's variance downwards; a negative length is invalid.
TEST(Refinement, TheStretchesTermOnlyWidensTheCovariance) {
  const RoomPair pair;
  const ContourRefiner refiner(pair.target, RefinementParams{});
  const std::vector<Eigen::Vector2d> samples = contourSamples(pair.source, RefinementModel{}.sample_step);
  const Eigen::Matrix3d start = matrixOf(test::pose2d(0.5, -0.05, 7));
  RefinementModel without;
  without.correlation_length = 0.0;
  const ContourRefiner plain_refiner(pair.target, RefinementParams{}, without);
  const RefinementResult plain = plain_refiner.refine(samples, start, RefinementParams{});
  const RefinementResult widened = refiner.refine(samples, start, RefinementParams{});
  EXPECT_TRUE(widened.transform.isApprox(plain.transform));
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> added(widened.covariance - plain.covariance);
  EXPECT_GE(added.eigenvalues().minCoeff(), -1e-12 * plain.covariance.norm());
  RefinementModel negative;
  negative.correlation_length = -1.0;
  std::string why;
  EXPECT_FALSE(negative.validate(&why));
  EXPECT_NE(why.find("correlation_length"), std::string::npos);
}

// Two views that share less of what they see get a wider covariance, by (0.8 / overlap)^2
// below an overlap of 0.8: the same pairs, with as many source samples again 100 m away (contour
// the target never saw), halve the overlap and leave the estimate and the residuals alone.
TEST(Refinement, TheCovarianceGrowsAsTheViewsShareLessOfTheContour) {
  const RoomPair pair;
  const ContourRefiner refiner(pair.target, RefinementParams{});
  const std::vector<Eigen::Vector2d> shared = contourSamples(pair.source, RefinementModel{}.sample_step);
  std::vector<Eigen::Vector2d> half_unseen = shared;
  for (const Eigen::Vector2d &p : shared) half_unseen.push_back(p + Eigen::Vector2d(100.0, 0.0));
  const Eigen::Matrix3d start = matrixOf(test::pose2d(0.5, -0.05, 7));
  const RefinementResult all = refiner.refine(shared, start, RefinementParams{});
  const RefinementResult half = refiner.refine(half_unseen, start, RefinementParams{});
  ASSERT_GT(all.overlap, 0.8);
  EXPECT_NEAR(half.overlap, all.overlap / 2, 1e-9);
  EXPECT_TRUE(half.transform.isApprox(all.transform));
  const double grown = std::pow(0.8 / half.overlap, 2);
  EXPECT_GT(grown, 2.0);
  const Eigen::Matrix2d translation = half.covariance.topLeftCorner<2, 2>() / grown;
  EXPECT_TRUE(translation.isApprox(all.covariance.topLeftCorner<2, 2>(), 1e-9));
  EXPECT_TRUE(half.information.isApprox(all.information / grown, 1e-9));
}

// The refinement stops only after a pass that paired at min_distance: a start already at the
// motion (its steps small from the first pass) still reports the overlap, rmse and covariance,
// stretches term included, of the final pairing distance.
TEST(Refinement, AStartAtTheMotionStillEndsWithAPassAtTheFinalPairingDistance) {
  const test::RoomWithBoxes room;
  const Eigen::Isometry2d motion = test::pose2d(0.4, -0.2, 5);
  const ContourFeatures target =
      extractContourFeatures(test::scanFrom(room.world, test::pose2d(0, 0, 0), 0.001, 3), ContourParams{});
  const ContourFeatures source = extractContourFeatures(test::scanFrom(room.world, motion, 0.001, 4), ContourParams{});
  const ContourRefiner refiner(target, RefinementParams{});
  const std::vector<Eigen::Vector2d> samples = contourSamples(source, RefinementModel{}.sample_step);
  Eigen::Matrix3d start = matrixOf(motion);
  for (int k = 0; k < 3; ++k) start = refiner.refine(samples, start, RefinementParams{}).transform;
  const RefinementResult at_motion = refiner.refine(samples, start, RefinementParams{});
  // 0.3 m shrinking by 0.7 per pass reaches 0.08 m in the fifth pass.
  EXPECT_GE(at_motion.iterations, 5);
}

}  // namespace
}  // namespace contour_reg
