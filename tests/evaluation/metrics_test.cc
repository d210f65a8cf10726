#include <cmath>

#include <gtest/gtest.h>

#include "contour_reg/evaluation/metrics.h"
#include "contour_reg/io/pose2d.h"

namespace contour_reg::evaluation {
namespace {

// A 10 m x 10 m square walked counter-clockwise, one pose per metre, stamps 0..40.
io::Trajectory square() {
  io::Trajectory t;
  double x = 0, y = 0;
  const double dx[] = {1, 0, -1, 0}, dy[] = {0, 1, 0, -1};
  for (int side = 0; side < 4; ++side)
    for (int step = 0; step < 10; ++step) {
      t.push_back({double(t.size()), {x, y, side * M_PI / 2}});
      x += dx[side];
      y += dy[side];
    }
  t.push_back({double(t.size()), {x, y, 2 * M_PI}});
  return t;
}

TEST(Metrics, PathLengthOfTheSquare) { EXPECT_NEAR(pathLength(square()), 40.0, 1e-12); }

TEST(Metrics, EndPointErrorIsOverThePathLength) {
  const io::Trajectory truth = square();
  io::Trajectory estimate = truth;
  estimate.back().pose.x += 0.6;
  estimate.back().pose.y += 0.8;
  const EndPointError e = endPointError(associate(estimate, truth));
  EXPECT_NEAR(e.error, 1.0, 1e-9);
  EXPECT_NEAR(e.path_length, 40.0, 1e-9);
  EXPECT_NEAR(e.percent, 2.5, 1e-9);
}

TEST(Metrics, EndPointErrorIgnoresWhereTheEstimateStarts) {
  const io::Trajectory truth = square();
  io::Trajectory estimate;
  const io::Pose2D offset{5.0, -2.0, 0.7};
  for (const auto &p : truth) estimate.push_back({p.stamp, io::compose(offset, p.pose)});
  EXPECT_NEAR(endPointError(associate(estimate, truth)).error, 0.0, 1e-9);
  EXPECT_NEAR(absoluteTrajectoryError(associate(estimate, truth)), 0.0, 1e-9);
}

TEST(Metrics, AteOfAConstantOffsetAfterAlignmentIsZeroAndOfNoiseIsItsRms) {
  const io::Trajectory truth = square();
  io::Trajectory estimate = truth;
  // Alternate +-0.1 m across the path: alignment cannot remove it.
  for (std::size_t k = 0; k < estimate.size(); ++k) estimate[k].pose.x += (k % 2 ? 0.1 : -0.1);
  EXPECT_NEAR(absoluteTrajectoryError(associate(estimate, truth)), 0.1, 0.002);
}

TEST(Metrics, DriftOfAOnePercentScaleErrorIsOnePercent) {
  io::Trajectory truth, estimate;
  for (int k = 0; k <= 100; ++k) {
    truth.push_back({double(k), {0.5 * k, 0.0, 0.0}});
    estimate.push_back({double(k), {0.505 * k, 0.0, 0.0}});
  }
  const Drift d = drift(associate(estimate, truth), 10.0);
  EXPECT_NEAR(d.mean_percent, 1.0, 1e-6);
  EXPECT_EQ(d.windows, 81u);  // starts 0..80 have 10 m ahead of them
}

TEST(Metrics, RelationErrorsOfAnExactTrajectoryAreZeroAndOfAShiftedOneAreTheShift) {
  const io::Trajectory truth = square();
  std::vector<io::Relation> relations;
  for (int k = 0; k + 3 < 40; k += 3)
    relations.push_back({double(k), double(k + 3), io::between(truth[k].pose, truth[k + 3].pose)});
  RelationErrors e = relationErrors(truth, relations);
  EXPECT_EQ(e.count, relations.size());
  EXPECT_NEAR(e.translation_mean, 0.0, 1e-9);
  EXPECT_NEAR(e.rotation_mean, 0.0, 1e-9);

  std::vector<io::Relation> off = relations;
  for (io::Relation &r : off) r.motion.x -= 0.2;  // every measured motion 0.2 m short along its own x
  e = relationErrors(truth, off);
  EXPECT_NEAR(e.translation_mean, 0.2, 1e-9);
  EXPECT_NEAR(e.translation_std, 0.0, 1e-9);

  relations.push_back({100.0, 101.0, {}});  // beyond the trajectory
  EXPECT_EQ(relationErrors(truth, relations).missing, 1u);
  EXPECT_EQ(relationErrors(truth, relations, 2.0).count, 0u);  // all are 3 s apart
}

TEST(Metrics, NormalisedErrorSquaredWeighsEachErrorByItsCovarianceAndTheReferenceFloor) {
  const io::Pose2D reference{1.0, 2.0, 0.1};
  // 3 cm off along x against a 3 cm standard deviation there: 1.
  Eigen::Matrix3d covariance = Eigen::Vector3d(0.03 * 0.03, 1e-4, 1e-4).asDiagonal();
  EXPECT_NEAR(normalisedErrorSquared({1.03, 2.0, 0.1}, reference, covariance, 0.0, 0.0), 1.0, 1e-9);
  // The reference's own 4 cm add to the 3 cm in quadrature: 5 cm, so 10 cm off gives 4.
  EXPECT_NEAR(normalisedErrorSquared({1.10, 2.0, 0.1}, reference, covariance, 0.04, 0.0), 4.0, 1e-9);
  // The yaw error is wrapped: 2 pi - 0.02 rad off is 0.02 rad off, against 0.01 rad: 4.
  covariance(2, 2) = 0.01 * 0.01;
  EXPECT_NEAR(normalisedErrorSquared({1.0, 2.0, 0.1 + 2 * M_PI - 0.02}, reference, covariance, 0.0, 0.0), 4.0, 1e-9);
  // Correlated x and y: an error along the long axis of the ellipse counts less than across it.
  covariance << 0.02, 0.018, 0, 0.018, 0.02, 0, 0, 0, 1e-4;
  const double along = normalisedErrorSquared({1.1, 2.1, 0.1}, reference, covariance, 0.0, 0.0);
  const double across = normalisedErrorSquared({1.1, 1.9, 0.1}, reference, covariance, 0.0, 0.0);
  EXPECT_NEAR(along, 0.02 / 0.038, 1e-9);   // (0.1, 0.1) on eigenvalue 0.038
  EXPECT_NEAR(across, 0.02 / 0.002, 1e-9);  // (0.1, -0.1) on eigenvalue 0.002
  // No covariance and no floor: nothing covers any error.
  EXPECT_TRUE(std::isinf(normalisedErrorSquared({1.01, 2.0, 0.1}, reference, Eigen::Matrix3d::Zero(), 0.0, 0.0)));
}

TEST(Metrics, PosesBetweenSamplesAreInterpolated) {
  const io::Trajectory t{{0.0, {0, 0, 0}}, {2.0, {2, 0, 0.2}}};
  const auto p = poseAt(t, 1.0, 3.0);
  ASSERT_TRUE(p);
  EXPECT_NEAR(p->yaw, 0.1, 1e-12);
  EXPECT_FALSE(poseAt(t, 2.5, 3.0));
  EXPECT_FALSE(poseAt(t, 1.0));  // samples more than the default 1 s apart
}

// A log that kept its stamps to six digits (1.01893e+09 for every scan): stamps that do not
// tell the poses apart. The metrics would pair every pose with one reference pose, a path of
// no length, and report a 0 % end-point error; they report nothing instead.
TEST(Metrics, StampsThatDoNotIncreaseGiveNoMetric) {
  const io::Trajectory truth = square();
  io::Trajectory estimate = truth;
  estimate.back().pose.x += 4.0;
  io::Trajectory same_stamps = estimate, same_truth = truth;
  for (auto &p : same_stamps) p.stamp = 1.01893e9;
  for (auto &p : same_truth) p.stamp = 1.01893e9;
  EXPECT_EQ(nonIncreasingStamps(truth), 0u);
  EXPECT_EQ(nonIncreasingStamps(same_stamps), 40u);

  const std::vector<io::Relation> relations{{1.01893e9, 1.01893e9, {}}};
  const Evaluation by_estimate = evaluate(same_stamps, &truth, &relations);
  EXPECT_EQ(by_estimate.estimate_stamps_not_increasing, 40u);
  EXPECT_FALSE(by_estimate.end_point);
  EXPECT_FALSE(by_estimate.ate);
  EXPECT_FALSE(by_estimate.relations_all);

  // The trajectory of such a log against the log's own poses, both stamped alike.
  const Evaluation alike = evaluate(same_stamps, &same_truth, nullptr);
  EXPECT_EQ(alike.ground_truth_stamps_not_increasing, 40u);
  EXPECT_FALSE(alike.end_point);
  EXPECT_FALSE(alike.drift);
  EXPECT_FALSE(alike.ate);

  // Stamps that increase: the 4 m error over the 40 m walked.
  const Evaluation stamped = evaluate(estimate, &truth, nullptr);
  ASSERT_TRUE(stamped.end_point);
  EXPECT_NEAR(stamped.end_point->percent, 10.0, 1e-9);
}

// A metric that does not apply is absent, not 0: a run shorter than the 10 m drift window has
// no drift, and a reference that does not move has no end-point error over its path length.
TEST(Metrics, ARunShorterThanTheWindowHasNoDriftAndOneStandingStillNoEndPointError) {
  io::Trajectory truth, estimate;
  for (int k = 0; k <= 10; ++k) {
    truth.push_back({double(k), {0.5 * k, 0.0, 0.0}});     // 5 m
    estimate.push_back({double(k), {0.6 * k, 0.0, 0.0}});  // 1 m too far at the end
  }
  const Evaluation short_run = evaluate(estimate, &truth, nullptr);
  ASSERT_TRUE(short_run.end_point);
  EXPECT_NEAR(short_run.end_point->percent, 20.0, 1e-9);
  EXPECT_FALSE(short_run.drift);
  ASSERT_TRUE(short_run.ate);

  io::Trajectory standing = truth;
  for (auto &p : standing) p.pose = {};
  const Evaluation still = evaluate(estimate, &standing, nullptr);
  EXPECT_FALSE(still.end_point);
  EXPECT_FALSE(still.drift);
  ASSERT_TRUE(still.ate);  // the positions' error needs no path
  EXPECT_GT(*still.ate, 1.0);
}

}  // namespace
}  // namespace contour_reg::evaluation
