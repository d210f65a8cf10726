#include "contour_reg/contour_registration.h"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>
#include <pcl/console/print.h>
#include <pcl/filters/filter.h>
#include <pcl/registration/icp.h>
#include <pcl/registration/ndt_2d.h>
#include <pcl/registration/transformation_estimation_2D.h>

#include "contour_reg/core/transform_estimation.h"
#include "scenes.h"

namespace contour_reg {
namespace {

using Cloud = pcl::PointCloud<pcl::PointXYZ>;

Cloud::Ptr toCloud(const LaserScan &scan) {
  auto cloud = pcl::make_shared<Cloud>();
  for (const Complex &c : polarCode(scan)) cloud->push_back(pcl::PointXYZ(float(c.real()), float(c.imag()), 0.0f));
  cloud->is_dense = false;
  return cloud;
}

// ICP and NDT need the invalid beams removed.
Cloud::Ptr finite(const Cloud::Ptr &cloud) {
  auto out = pcl::make_shared<Cloud>();
  pcl::Indices kept;
  pcl::removeNaNFromPointCloud(*cloud, *out, kept);
  return out;
}

// Scans of the furnished room from a target pose and from target * motion.
struct ScanPair {
  Eigen::Isometry2d motion = test::pose2d(0.35, -0.15, 12);
  Cloud::Ptr target, source;
  ScanPair() {
    const simulation::World world = simulation::makeFurnishedRoom();
    const Eigen::Isometry2d base = test::pose2d(0.5, -0.4, 20);
    target = toCloud(test::scanFrom(world, base, 0.01, 1));
    source = toCloud(test::scanFrom(world, base * motion, 0.01, 2));
  }
  double translationError(const Eigen::Matrix4f &t) const {
    return (t.block<2, 1>(0, 3).cast<double>() - motion.translation()).norm();
  }
  double yawErrorDeg(const Eigen::Matrix4f &t) const {
    const double yaw = std::atan2(t(1, 0), t(0, 0)), truth = std::atan2(motion.linear()(1, 0), motion.linear()(0, 0));
    return std::abs(std::remainder(yaw - truth, 2 * M_PI)) * 180 / M_PI;
  }
};

TEST(ContourRegistration, AlignsLikeTheCore) {
  const ScanPair pair;
  ContourRegistration<pcl::PointXYZ, pcl::PointXYZ> registration;
  registration.setInputSource(pair.source);
  registration.setInputTarget(pair.target);
  Cloud aligned;
  registration.align(aligned);
  ASSERT_TRUE(registration.hasConverged()) << registration.getFailureReason();
  const Eigen::Matrix4f t = registration.getFinalTransformation();
  EXPECT_LT(pair.translationError(t), 0.02);
  EXPECT_LT(pair.yawErrorDeg(t), 0.5);
  EXPECT_EQ(aligned.size(), pair.source->size());
  EXPECT_LT(registration.getFitnessScore(0.25), 0.005);  // PCL's score through the lazily built tree

  // The core on the same clouds, with the same seed.
  const ContourFeatures source = extractContourFeatures(polarCodeFromCloud(*pair.source), ContourParams{});
  const ContourFeatures target = extractContourFeatures(polarCodeFromCloud(*pair.target), ContourParams{});
  std::mt19937 rng(42);
  const Eigen::Matrix3d identity = Eigen::Matrix3d::Identity();
  const RegistrationResult core = registerContours(source, target, RegistrationParams{}, rng, &identity);
  ASSERT_TRUE(core.converged);
  EXPECT_NEAR(t(0, 3), core.transform(0, 2), 1e-5);
  EXPECT_NEAR(t(1, 3), core.transform(1, 2), 1e-5);
  EXPECT_NEAR(std::atan2(t(1, 0), t(0, 0)), yawOf(core.transform), 1e-5);
  EXPECT_EQ(registration.getResult().inliers, core.inliers);
}

TEST(ContourRegistration, StandsWhereIcpAndNdtStand) {
  const ScanPair pair;
  using Registration = pcl::Registration<pcl::PointXYZ, pcl::PointXYZ>;
  std::vector<std::pair<std::string, Registration::Ptr>> methods;
  methods.emplace_back("contour", pcl::make_shared<ContourRegistration<pcl::PointXYZ, pcl::PointXYZ>>());
  auto icp = pcl::make_shared<pcl::IterativeClosestPoint<pcl::PointXYZ, pcl::PointXYZ>>();
  icp->setTransformationEstimation(
      pcl::make_shared<pcl::registration::TransformationEstimation2D<pcl::PointXYZ, pcl::PointXYZ>>());
  icp->setMaxCorrespondenceDistance(1.0);
  icp->setMaximumIterations(50);
  methods.emplace_back("icp", icp);
  auto ndt = pcl::make_shared<pcl::NormalDistributionsTransform2D<pcl::PointXYZ, pcl::PointXYZ>>();
  ndt->setGridCentre(Eigen::Vector2f(0, 0));
  ndt->setGridExtent(Eigen::Vector2f(20, 20));
  ndt->setGridStep(Eigen::Vector2f(0.5, 0.5));
  ndt->setMaximumIterations(50);
  ndt->setTransformationEpsilon(1e-6);
  methods.emplace_back("ndt2d", ndt);

  // ICP and NDT2D need finite points; all methods get the same filtered clouds.
  const Cloud::Ptr source = finite(pair.source), target = finite(pair.target);
  for (auto &[name, method] : methods) {
    SCOPED_TRACE(name);
    method->setInputSource(source);
    method->setInputTarget(target);
    Cloud aligned;
    method->align(aligned);
    EXPECT_EQ(aligned.size(), source->size());
    if (name == "contour") {
      ASSERT_TRUE(method->hasConverged());
      EXPECT_LT(pair.translationError(method->getFinalTransformation()), 0.02);
    }
  }
}

TEST(ContourRegistration, ReusesThePreviousSourceAsTarget) {
  const simulation::World world = simulation::makeFurnishedRoom();
  ContourRegistration<pcl::PointXYZ, pcl::PointXYZ> registration;
  Cloud::Ptr previous = toCloud(test::scanFrom(world, test::pose2d(0, 0, 0), 0.01, 1));
  for (int k = 1; k <= 3; ++k) {
    const Cloud::Ptr current = toCloud(test::scanFrom(world, test::pose2d(0.2 * k, 0.05 * k, 3 * k), 0.01, 1 + k));
    registration.setInputTarget(previous);
    registration.setInputSource(current);
    Cloud aligned;
    registration.align(aligned);
    ASSERT_TRUE(registration.hasConverged());
    const Eigen::Matrix4f t = registration.getFinalTransformation();
    const Eigen::Isometry2d truth = test::pose2d(0.2 * (k - 1), 0.05 * (k - 1), 3 * (k - 1)).inverse() *
                                    test::pose2d(0.2 * k, 0.05 * k, 3 * k);
    EXPECT_LT((t.block<2, 1>(0, 3).cast<double>() - truth.translation()).norm(), 0.02);
    // The target's special points are those the previous align() found in this cloud.
    if (k > 1) {
      EXPECT_EQ(registration.getTargetFeatures().special_points.size(),
                extractContourFeatures(polarCodeFromCloud(*previous), ContourParams{}).special_points.size());
    }
    previous = current;
  }
}

TEST(ContourRegistration, EmptyAndAllNanCloudsFailThePclWay) {
  const auto verbosity = pcl::console::getVerbosityLevel();
  pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
  const ScanPair pair;
  ContourRegistration<pcl::PointXYZ, pcl::PointXYZ> registration;
  auto empty = pcl::make_shared<Cloud>();
  auto all_nan = pcl::make_shared<Cloud>();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  all_nan->resize(360, pcl::PointXYZ(nan, nan, nan));
  all_nan->is_dense = false;
  Eigen::Matrix4f guess = Eigen::Matrix4f::Identity();
  guess(0, 3) = 0.3f;
  for (const Cloud::Ptr &bad : {empty, all_nan}) {
    for (bool bad_source : {true, false}) {
      registration.setInputSource(bad_source ? bad : pair.source);
      registration.setInputTarget(bad_source ? pair.target : bad);
      Cloud aligned;
      registration.align(aligned, guess);
      EXPECT_FALSE(registration.hasConverged());
      EXPECT_FALSE(registration.getFailureReason().empty());
      EXPECT_TRUE(registration.getFinalTransformation().isApprox(guess));  // the guess, not a made-up pose
    }
  }
  pcl::console::setVerbosityLevel(verbosity);
}

TEST(ContourRegistration, CorridorReportsWhyItDidNotConverge) {
  simulation::World corridor;
  corridor.addSegment({-30, -1.2}, {30, -1.2});
  corridor.addSegment({-30, 1.3}, {30, 1.3});
  ContourRegistration<pcl::PointXYZ, pcl::PointXYZ> registration;
  registration.setInputTarget(toCloud(test::scanFrom(corridor, test::pose2d(0, 0, 0), 0.01, 1)));
  registration.setInputSource(toCloud(test::scanFrom(corridor, test::pose2d(0.4, 0, 2), 0.01, 2)));
  Cloud aligned;
  registration.align(aligned);
  EXPECT_FALSE(registration.hasConverged());
  EXPECT_NE(registration.getFailureReason().find("special points"), std::string::npos);
  // PCL's ICP, on the same pair, reports convergence although the corridor fixes nothing along its axis.
  pcl::IterativeClosestPoint<pcl::PointXYZ, pcl::PointXYZ> icp;
  icp.setInputSource(finite(toCloud(test::scanFrom(corridor, test::pose2d(0.4, 0, 2), 0.01, 2))));
  icp.setInputTarget(finite(toCloud(test::scanFrom(corridor, test::pose2d(0, 0, 0), 0.01, 1))));
  icp.align(aligned);
  EXPECT_TRUE(icp.hasConverged());
  EXPECT_GT(std::abs(icp.getFinalTransformation()(0, 3) - 0.4f), 0.1f);
}

}  // namespace
}  // namespace contour_reg
