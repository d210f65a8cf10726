// The wheels' motion model and the fusion of a scan's motion with the wheels' (wheel_fusion.h).
#include <cmath>

#include <gtest/gtest.h>
#include <Eigen/LU>

#include "contour_reg/odometry/wheel_fusion.h"

namespace contour_reg::odometry {
namespace {

WheelNoise noise() {
  WheelNoise n;
  n.rotation_per_rotation = 0.01;
  n.rotation_per_translation = 0.002;
  n.translation_per_translation = 0.04;
  n.translation_per_rotation = 0.001;
  n.translation_floor = 0.01;
  n.rotation_floor = 0.005;
  return n;
}

// A straight drive of t m: along it alpha3 t^2, across it the turn r1's alpha2 t^2 times the
// lever t, in yaw both turns' alpha2 t^2; each with its floor.
TEST(WheelNoise, AStraightDriveHasTheModelsVariances) {
  const WheelNoise n = noise();
  const double t = 0.5;
  const Eigen::Matrix3d c = wheelCovariance({t, 0.0, 0.0}, n);
  EXPECT_NEAR(c(0, 0), 0.04 * t * t + 1e-4, 1e-12);
  EXPECT_NEAR(c(1, 1), t * t * 0.002 * t * t + 1e-4, 1e-12);
  EXPECT_NEAR(c(2, 2), 2 * 0.002 * t * t + 25e-6, 1e-12);
  EXPECT_NEAR(c(1, 2), t * 0.002 * t * t, 1e-12);  // a turn at the start moves the end sideways
  EXPECT_NEAR(c(0, 1), 0.0, 1e-12);
}

TEST(WheelNoise, ADriveBackwardsIsAsUncertainAsForwards) {
  const Eigen::Matrix3d forwards = wheelCovariance({0.4, 0.1, 0.2}, noise());
  const Eigen::Matrix3d backwards = wheelCovariance({-0.4, -0.1, 0.2}, noise());
  // The same drive mirrored through the start: the translation's sign turns, and with it its
  // correlation with the yaw.
  const Eigen::Matrix3d mirror = Eigen::Vector3d(-1.0, -1.0, 1.0).asDiagonal();
  EXPECT_TRUE(backwards.isApprox(mirror * forwards * mirror, 1e-9)) << backwards << "\n" << forwards;
}

TEST(WheelNoise, StandingStillLeavesTheFloor) {
  const Eigen::Matrix3d c = wheelCovariance({0.0, 0.0, 0.0}, noise());
  EXPECT_TRUE(c.isApprox(Eigen::Vector3d(1e-4, 1e-4, 25e-6).asDiagonal().toDenseMatrix(), 1e-12)) << c;
}

TEST(WheelNoise, RejectsNegativeOrMissingNoise) {
  WheelNoise n = noise();
  EXPECT_TRUE(n.validate());
  n.translation_per_translation = -1.0;
  std::string why;
  EXPECT_FALSE(n.validate(&why));
  EXPECT_FALSE(why.empty());
  n = noise();
  n.rotation_floor = 0.0;
  EXPECT_FALSE(n.validate());
}

// Along x the scans know nothing (a corridor's axis): the wheels decide x, the scans y and yaw.
TEST(Fusion, TheWheelsDecideTheDirectionTheScansLeaveFree) {
  const io::Pose2D scan{0.0, 0.05, 0.02}, wheel{0.48, 0.2, 0.1};
  const Eigen::Matrix3d scan_information = Eigen::Vector3d(0.0, 1e6, 1e7).asDiagonal();
  const Eigen::Matrix3d wheel_covariance = Eigen::Vector3d(4e-4, 4e-4, 1e-3).asDiagonal();
  const auto fused = fuse(scan, scan_information, wheel, wheel_covariance);
  ASSERT_TRUE(fused);
  EXPECT_NEAR(fused->motion.x, 0.48, 1e-9);
  EXPECT_NEAR(fused->motion.y, 0.05, 1e-3);
  EXPECT_NEAR(fused->motion.yaw, 0.02, 1e-3);
  EXPECT_NEAR(fused->covariance(0, 0), 4e-4, 1e-12);  // the wheels' alone
  EXPECT_LT(fused->covariance(1, 1), 1.01e-6);
}

// Two equally sure measurements: the mean, with half the variance; the yaw wrapped across pi.
TEST(Fusion, EqualCertaintyGivesTheMean) {
  const Eigen::Matrix3d information = Eigen::Vector3d(100.0, 100.0, 400.0).asDiagonal();
  const auto fused = fuse({0.2, 0.0, M_PI - 0.01}, information, {0.4, 0.1, -M_PI + 0.03}, information.inverse());
  ASSERT_TRUE(fused);
  EXPECT_NEAR(fused->motion.x, 0.3, 1e-9);
  EXPECT_NEAR(fused->motion.y, 0.05, 1e-9);
  EXPECT_NEAR(std::remainder(fused->motion.yaw - (M_PI + 0.01), 2 * M_PI), 0.0, 1e-9);
  EXPECT_TRUE(fused->covariance.isApprox(0.5 * information.inverse(), 1e-9));
  // Each half the difference d away: d^T I d / 2 = (100 * 0.04 + 100 * 0.01 + 400 * 0.0016) / 2.
  EXPECT_NEAR(fused->disagreement, 2.82, 1e-9);
}

TEST(Fusion, RefusesAWheelCovarianceThatIsNotPositive) {
  EXPECT_FALSE(fuse({}, Eigen::Matrix3d::Identity(), {}, Eigen::Matrix3d::Zero()));
}

// A wheel increment of 1e300 m (a corrupt sample) has a covariance beyond any double: nothing
// to fuse, where its arithmetic would give NaN.
TEST(Fusion, RefusesAWheelIncrementThatIsNotFinite) {
  const Eigen::Matrix3d information = Eigen::Vector3d(1e4, 1e4, 1e5).asDiagonal();
  const io::Pose2D absurd{1e300, 0.0, 0.1};
  EXPECT_FALSE(fuse({0.1, 0.0, 0.1}, information, absurd, wheelCovariance(absurd, noise())));
  const io::Pose2D unknown{std::nan(""), 0.0, 0.1};
  EXPECT_FALSE(fuse({0.1, 0.0, 0.1}, information, unknown, Eigen::Matrix3d::Identity()));
}

}  // namespace
}  // namespace contour_reg::odometry
