#include "contour_reg/evaluation/closure.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>
#include <Eigen/Dense>

#include "contour_reg/evaluation/metrics.h"
#include "contour_reg/io/pose2d.h"

namespace contour_reg::evaluation {
namespace {

const io::Pose2D kAb{1.2, 0.3, 0.4}, kBc{0.8, -0.5, -0.7};

Eigen::Matrix3d covariance(double metres, double radians, double correlation) {
  Eigen::Matrix3d c;
  c << metres * metres, correlation * metres * metres, correlation * metres * radians, correlation * metres * metres,
      metres * metres, 0.0, correlation * metres * radians, 0.0, radians * radians;
  return c;
}

// ac^-1 ab bc, as the composition of the three motions.
Eigen::Vector3d closureOf(const io::Pose2D &ab, const io::Pose2D &bc, const io::Pose2D &ac) {
  const io::Pose2D d = io::toPose(io::toMatrix(ac).inverse() * io::toMatrix(ab) * io::toMatrix(bc));
  return {d.x, d.y, d.yaw};
}

io::Pose2D perturbed(const io::Pose2D &p, const Eigen::Matrix3d &c, std::mt19937 &rng) {
  std::normal_distribution<double> normal;
  const Eigen::Vector3d e = Eigen::Matrix3d(c.llt().matrixL()) * Eigen::Vector3d(normal(rng), normal(rng), normal(rng));
  return {p.x + e(0), p.y + e(1), p.yaw + e(2)};
}

TEST(TriangleClosure, ThreeConsistentMotionsClose) {
  const io::Pose2D ac = io::compose(kAb, kBc);
  const TriangleClosure closure = triangleClosure(kAb, covariance(0.01, 0.01, 0.3), kBc, covariance(0.02, 0.005, 0.0),
                                                  ac, covariance(0.01, 0.01, -0.2));
  EXPECT_LT(closure.error.norm(), 1e-12);
  EXPECT_LT(closure.nees, 1e-18);
}

TEST(TriangleClosure, AnOffsetOfTheLongMotionIsWeighedByAllThreeCovariances) {
  // ab and bc no motion, ac 3 cm ahead: the closure is 3 cm back, its variance the three
  // translation variances summed (the yaw's lever, t_D, is 3 cm: negligible at 1e-8 rad^2).
  const Eigen::Matrix3d c = covariance(0.01, 1e-4, 0.0);
  const TriangleClosure closure = triangleClosure({0, 0, 0}, c, {0, 0, 0}, c, {0.03, 0, 0}, c);
  EXPECT_NEAR(closure.error(0), -0.03, 1e-12);
  EXPECT_NEAR(closure.error(1), 0.0, 1e-12);
  EXPECT_NEAR(closure.covariance(0, 0), 3e-4, 1e-9);
  EXPECT_NEAR(closure.nees, 0.03 * 0.03 / 3e-4, 1e-3);
}

// Motions drawn from their covariances: the closure's covariance is the spread of the
// closures they give, and its NEES follows chi-square with 3 degrees of freedom (mean 3, 1 %
// above kNees99); covariances claimed four times too small give four times the NEES.
TEST(TriangleClosure, HonestCovariancesGiveChiSquareAndOverConfidentOnesShow) {
  const Eigen::Matrix3d c_ab = covariance(0.02, 0.01, 0.4), c_bc = covariance(0.015, 0.02, -0.3),
                        c_ac = covariance(0.025, 0.008, 0.2);
  const io::Pose2D ac = io::compose(kAb, kBc);
  std::mt19937 rng(7);
  const int n = 20000;
  Eigen::Matrix3d spread = Eigen::Matrix3d::Zero();
  double nees = 0.0, nees_over_confident = 0.0;
  int outside = 0;
  Eigen::Matrix3d predicted = Eigen::Matrix3d::Zero();
  for (int k = 0; k < n; ++k) {
    const io::Pose2D ab = perturbed(kAb, c_ab, rng), bc = perturbed(kBc, c_bc, rng),
                     ac_drawn = perturbed(ac, c_ac, rng);
    const Eigen::Vector3d e = closureOf(ab, bc, ac_drawn);
    spread += e * e.transpose() / n;
    const TriangleClosure closure = triangleClosure(ab, c_ab, bc, c_bc, ac_drawn, c_ac);
    EXPECT_NEAR((closure.error - e).norm(), 0.0, 1e-9);
    predicted = closure.covariance;
    nees += closure.nees / n;
    outside += closure.nees > kNees99;
    nees_over_confident += triangleClosure(ab, c_ab / 4, bc, c_bc / 4, ac_drawn, c_ac / 4).nees / n;
  }
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(spread(i, i), predicted(i, i), 0.05 * predicted(i, i)) << "component " << i;
  EXPECT_NEAR(nees, 3.0, 0.1);
  EXPECT_NEAR(static_cast<double>(outside) / n, 0.01, 0.003);
  EXPECT_NEAR(nees_over_confident, 12.0, 0.5);
}

TEST(TriangleClosure, ZeroCovariancesGiveAnInfiniteNees) {
  const Eigen::Matrix3d zero = Eigen::Matrix3d::Zero();
  EXPECT_TRUE(std::isinf(triangleClosure(kAb, zero, kBc, zero, {0, 0, 0}, zero).nees));
}

}  // namespace
}  // namespace contour_reg::evaluation
