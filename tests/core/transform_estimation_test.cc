#include "contour_reg/core/transform_estimation.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "contour_reg/core/ransac.h"

namespace contour_reg {
namespace {

Eigen::Vector2d apply(const Eigen::Matrix3d &h, const Eigen::Vector2d &p) {
  return h.topLeftCorner<2, 2>() * p + h.topRightCorner<2, 1>();
}

TEST(TransformEstimation, RigidFitRecoversAnExactMotion) {
  const Eigen::Matrix3d truth = rigidTransform(0.7, -0.3, 0.6);
  const Points2D p = {{0, 0}, {1, 0}, {3, 2}, {-1, 4}};
  Points2D q;
  for (const auto &x : p) q.push_back(apply(truth, x));
  Eigen::Matrix3d fit;
  ASSERT_TRUE(estimateRigid(p, q, fit));
  EXPECT_TRUE(fit.isApprox(truth, 1e-12));
  EXPECT_FALSE(estimateRigid({{1, 1}}, {{2, 2}}, fit));
  EXPECT_FALSE(estimateRigid({{1, 1}, {1, 1}}, {{2, 2}, {2, 2}}, fit));
}

TEST(TransformEstimation, AffineFitSolvesTheNormalEquations) {  // eq. (17)
  Eigen::Matrix3d truth;
  truth << 1.1, 0.2, 0.5, -0.1, 0.9, -2.0, 0, 0, 1;
  const Points2D p = {{0, 0}, {1, 0}, {0, 1}, {2, 3}, {-1, 2}};
  Points2D q;
  for (const auto &x : p) q.push_back(apply(truth, x));
  Eigen::Matrix3d fit;
  ASSERT_TRUE(estimateAffine(p, q, fit));
  EXPECT_TRUE(fit.isApprox(truth, 1e-9));
  // Collinear points leave the affine map undetermined.
  EXPECT_FALSE(estimateAffine({{0, 0}, {1, 1}, {2, 2}}, {{0, 0}, {1, 1}, {2, 2}}, fit));
}

TEST(TransformEstimation, RigidPartOfARotationIsItself) {
  const Eigen::Matrix3d rigid = rigidTransform(1, 2, -2.5);
  EXPECT_TRUE(rigidPart(rigid).isApprox(rigid, 1e-12));
  EXPECT_NEAR(yawOf(rigid), -2.5, 1e-12);
}

TEST(TransformEstimation, RigidPartOfAnAffineMapIsTheNearestRotation) {
  // R diag(a, b) = R P with P symmetric and positive: its polar decomposition, whose rotation
  // is the nearest in Frobenius norm. The translation is kept.
  const Eigen::Matrix3d rotation = rigidTransform(0.0, 0.0, 2.2);
  Eigen::Matrix3d affine = Eigen::Matrix3d::Identity();
  affine.topLeftCorner<2, 2>() = rotation.topLeftCorner<2, 2>() * Eigen::Vector2d(1.3, 0.6).asDiagonal();
  affine.topRightCorner<2, 1>() = Eigen::Vector2d(-0.4, 3.0);
  EXPECT_TRUE(rigidPart(affine).isApprox(rigidTransform(-0.4, 3.0, 2.2), 1e-12)) << rigidPart(affine);
  // No linear part: no rotation to take, the identity's.
  Eigen::Matrix3d flat = Eigen::Matrix3d::Identity();
  flat.topLeftCorner<2, 2>().setZero();
  flat(0, 2) = 1.0;
  EXPECT_TRUE(rigidPart(flat).isApprox(rigidTransform(1.0, 0.0, 0.0), 1e-12)) << rigidPart(flat);
}

class RansacTest : public ::testing::TestWithParam<TransformModel> {};

TEST_P(RansacTest, FindsTheMotionAmongOutliersRepeatably) {
  std::mt19937 prng(42);
  std::uniform_real_distribution<double> u(-5, 5);
  const Eigen::Matrix3d truth = rigidTransform(0.4, 0.2, 0.3);
  Points2D p, q;
  for (int i = 0; i < 12; ++i) {
    p.emplace_back(u(prng), u(prng));
    q.push_back(apply(truth, p.back()));
  }
  for (int i = 0; i < 8; ++i) {  // 40 % outliers
    p.emplace_back(u(prng), u(prng));
    q.emplace_back(u(prng), u(prng));
  }
  RansacParams params;
  params.model = GetParam();
  std::mt19937 rng1(7), rng2(7);
  const RansacResult a = ransac(p, q, {}, params, rng1);
  const RansacResult b = ransac(p, q, {}, params, rng2);
  ASSERT_TRUE(a.found);
  EXPECT_EQ(a.inliers.size(), 12u);
  EXPECT_TRUE(a.transform.isApprox(truth, 1e-9));
  EXPECT_EQ(a.inliers, b.inliers);
  EXPECT_EQ(a.transform, b.transform);
}

INSTANTIATE_TEST_SUITE_P(Models, RansacTest, ::testing::Values(TransformModel::kRigid, TransformModel::kAffine));

}  // namespace
}  // namespace contour_reg
