// Degenerate scenes report "not converged" or "degenerate" with the reason, and the
// covariance of a converged estimate is consistent with its actual errors.
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

// Registers the scan `lidar` takes at `motion` in `after` onto the one it takes at the origin
// in `before`.
RegistrationResult registerBetween(const simulation::World &before, const simulation::World &after,
                                   const Eigen::Isometry2d &motion, const simulation::LidarModel &lidar, unsigned seed,
                                   const decision::Checks &checks = {}) {
  std::mt19937 target_noise(seed), source_noise(seed + 1000), rng(seed);
  const ContourFeatures target = extractContourFeatures(
      simulation::simulateScan(before, test::pose2d(0, 0, 0), lidar, target_noise), ContourParams{});
  const ContourFeatures source =
      extractContourFeatures(simulation::simulateScan(after, motion, lidar, source_noise), ContourParams{});
  return decision::registerContoursWith(source, target, RegistrationParams{}, checks, rng);
}

// The same in one unchanging world.
RegistrationResult registerFrom(const simulation::World &world, const Eigen::Isometry2d &motion,
                                const simulation::LidarModel &lidar, unsigned seed) {
  return registerBetween(world, world, motion, lidar, seed);
}

// The same with the Hokuyo-like LIDAR of `noise` m range noise.
RegistrationResult registerFrom(const simulation::World &world, const Eigen::Isometry2d &motion, double noise,
                                unsigned seed) {
  simulation::LidarModel lidar = simulation::LidarModel::hokuyoUtm30lx();
  lidar.range_noise = noise;
  return registerFrom(world, motion, lidar, seed);
}

// The mean normalised estimation error squared of the converged estimates of 60 seeded motions
// (up to 0.3 m and 5 deg) from the room `before` to the room `after`, seen by `lidar`.
double meanNees(const simulation::World &before, const simulation::World &after, const simulation::LidarModel &lidar,
                const decision::Checks &checks = {}) {
  std::mt19937 draw(2024);
  std::uniform_real_distribution<double> shift(-0.3, 0.3), turn(-5.0, 5.0);
  double sum = 0.0;
  int trials = 0;
  for (unsigned seed = 1; seed <= 60; ++seed) {
    const Eigen::Isometry2d motion = test::pose2d(shift(draw), shift(draw), turn(draw));
    const RegistrationResult r = registerBetween(before, after, motion, lidar, seed, checks);
    if (!r.converged) continue;
    const Eigen::Matrix3d truth = motion.matrix();
    const Eigen::Vector3d error(r.transform(0, 2) - truth(0, 2), r.transform(1, 2) - truth(1, 2),
                                std::remainder(yawOf(r.transform) - yawOf(truth), 2.0 * M_PI));
    EXPECT_GT(r.covariance.determinant(), 0.0);
    sum += error.dot(r.covariance.ldlt().solve(error));
    ++trials;
  }
  EXPECT_GE(trials, 50);
  return sum / std::max(trials, 1);
}

// The same in the furnished room.
double meanNees(const simulation::LidarModel &lidar) {
  const simulation::World room = simulation::makeFurnishedRoom();
  return meanNees(room, room, lidar);
}

TEST(Degeneracy, SingleWallDoesNotConverge) {
  simulation::World wall;
  wall.addSegment({-20.0, 2.0}, {20.0, 2.0});
  const RegistrationResult r = registerFrom(wall, test::pose2d(0.4, 0.1, 2), 0.01, 1);
  EXPECT_FALSE(r.converged) << r.transform;
  EXPECT_FALSE(r.reason.empty());
}

TEST(Degeneracy, TwoPointsDoNotConverge) {
  // Two small posts: a handful of returns, no contour long enough for a corner.
  simulation::World posts;
  posts.addCircle({2.0, 1.0}, 0.05);
  posts.addCircle({3.0, -1.5}, 0.05);
  const RegistrationResult r = registerFrom(posts, test::pose2d(0.2, 0.0, 0), 0.01, 2);
  EXPECT_FALSE(r.converged);
  EXPECT_TRUE(isUndecided(r.status));
  EXPECT_NE(r.reason.find("too few special points: 0 in source, 0 in target"), std::string::npos) << r.reason;
  EXPECT_EQ(r.status, RegistrationStatus::kUnconstrained) << r.reason;  // the contours' verdict on two posts
}

TEST(Degeneracy, CorridorRefinementIsFlaggedDegenerate) {
  // Two parallel walls with one doorway corner pair: if anything converges, the contour
  // refinement must see that the corridor axis is weakly constrained or the answer must be right.
  const simulation::World corridor = test::bareCorridor(30);
  const Eigen::Isometry2d motion = test::pose2d(0.5, 0.05, 1);
  const RegistrationResult r = registerFrom(corridor, motion, 0.01, 3);
  if (r.converged) {
    const Eigen::Matrix3d truth = motion.matrix();
    EXPECT_NEAR(r.transform(0, 2), truth(0, 2), 0.05) << "a corridor answer claimed as converged is wrong";
  } else {
    EXPECT_FALSE(r.reason.empty());
  }
}

// A bare corridor: the verdict is unconstrained, and what the contours pin is right across the
// axis and in heading, with no information along the axis.
TEST(Degeneracy, ABareCorridorPinsItsCrossAxisAndHeading) {
  const simulation::World corridor = test::bareCorridor(100);
  const Eigen::Isometry2d motion = test::pose2d(0.5, 0.05, 1);
  const RegistrationResult r = registerFrom(corridor, motion, 0.01, 3);
  ASSERT_FALSE(r.converged);
  EXPECT_EQ(r.status, RegistrationStatus::kUnconstrained) << r.reason;
  EXPECT_TRUE(r.transform.isIdentity()) << "without a guess, a failure reports the identity";
  ASSERT_TRUE(r.pinned.has_value());
  const PinnedMotion &pinned = *r.pinned;
  // The free direction is the axis, x, up to sign.
  EXPECT_GT(std::abs(pinned.free_direction.normalized()(0)), 0.99) << pinned.free_direction.transpose();
  EXPECT_LT((pinned.information * pinned.free_direction).norm(),
            1e-6 * pinned.information.norm() * pinned.free_direction.norm());
  // Across the axis and in heading the pinned motion is the true one (the source seen from
  // y 0.05 turned 1 deg, wherever along the axis).
  EXPECT_NEAR(pinned.transform(1, 2), 0.05, 0.01);
  EXPECT_NEAR(yawOf(pinned.transform) * 180.0 / M_PI, 1.0, 0.2);
  // And those two directions are sure: centimetres, tenths of a degree.
  EXPECT_GT(pinned.information(1, 1), 1.0 / (0.01 * 0.01));
  EXPECT_GT(pinned.information(2, 2), 1.0 / std::pow(0.2 * M_PI / 180.0, 2));
}

// A room pins every direction: nothing is reported as pinned only.
TEST(Degeneracy, ARoomLeavesNoDirectionFree) {
  const RegistrationResult r = registerFrom(simulation::makeFurnishedRoom(), test::pose2d(0.3, 0.1, 5), 0.01, 4);
  ASSERT_TRUE(r.converged) << r.reason;
  EXPECT_FALSE(r.pinned.has_value());
}

// Normalised estimation error squared of the rigid estimate against its covariance, averaged
// over seeded trials: near 3 (x, y, yaw) when the covariance describes the actual errors. In
// this room with the Hokuyo it is 1.7: the covariance, calibrated on real logs (mean NEES 2.8-3.0
// on fr079 and mit-csail, docs/reliability.md), is a little wide on these clean walls.
TEST(Covariance, NormalisedErrorSquaredIsNearThreeDegreesOfFreedom) {
  simulation::LidarModel lidar = simulation::LidarModel::hokuyoUtm30lx();  // 0.25 deg, 1 cm noise
  const double nees = meanNees(lidar);
  std::printf("average NEES: %.2f\n", nees);
  EXPECT_GT(nees, 1.5);
  EXPECT_LT(nees, 4.5);
}

// Beams 2 deg apart (a low-cost LIDAR's) meet the room's walls 10-40 cm apart, so several
// contour samples lie between the same two returns and share their noise: counted as
// independent, they make the covariance too small (mean 6.4). Counted once per sample step of
// the returns' spacing, the mean stays near 3.
TEST(Covariance, SparseBeamsCountTheirSharedNoiseOnce) {
  simulation::LidarModel lidar;
  lidar.beams = 180;
  lidar.field_of_view = 2.0 * M_PI * (180.0 - 1.0) / 180.0;
  lidar.range_noise = 0.02;
  const double nees = meanNees(lidar);
  std::printf("average NEES: %.2f\n", nees);
  EXPECT_GT(nees, 2.0);
  EXPECT_LT(nees, 4.5);
}

// The furnished room with a cart, 0.8 x 0.6 m, whose near side stands at x = `near_side` m.
simulation::World furnishedRoomWithCartAt(double near_side) {
  simulation::World world = simulation::makeFurnishedRoom();
  world.addBox({near_side, 0.4}, {near_side + 0.8, 1.0});
  return world;
}

// The mean NEES when the cart has been pushed 5 cm between the scans: a stretch of contour that
// disagrees with the rest, as a nudged chair or a door left ajar does.
double meanNeesWithMovedCart(double correlation_length) {
  decision::Checks checks;
  checks.refinement_model.correlation_length = correlation_length;
  return meanNees(furnishedRoomWithCartAt(3.0), furnishedRoomWithCartAt(3.05), simulation::LidarModel::hokuyoUtm30lx(),
                  checks);
}

TEST(Covariance, StretchesOfContourThatDisagreeWidenIt) {
  const double with = meanNeesWithMovedCart(RefinementModel{}.correlation_length);
  const double without = meanNeesWithMovedCart(0.0);
  std::printf("average NEES with a moved cart: %.2f, %.2f without the stretches' term\n", with, without);
  EXPECT_LT(with, 4.0);
  EXPECT_GT(without, 4.5);
}

}  // namespace
}  // namespace contour_reg
