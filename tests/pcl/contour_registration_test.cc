#include "contour_reg/contour_registration.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <random>

#include <gtest/gtest.h>
#include <pcl/console/print.h>
#include <pcl/filters/filter.h>
#include <pcl/registration/icp.h>
#include <pcl/registration/ndt_2d.h>
#include <pcl/registration/transformation_estimation_2D.h>

#include "contour_reg/core/deskew.h"
#include "contour_reg/core/transform_estimation.h"
#include "contour_reg/odometry/scan_matcher.h"
#include "scenes.h"

namespace contour_reg {
namespace {

using Cloud = pcl::PointCloud<pcl::PointXYZ>;

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
    target = odometry::beamCloud(test::scanFrom(world, base, 0.01, 1));
    source = odometry::beamCloud(test::scanFrom(world, base * motion, 0.01, 2));
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

// PCL's visualisation callback (pcl::RegistrationVisualizer's hook) is called after align()
// with the moved source and the corner pairs that decided the motion, as ICP calls it with its
// correspondences: each source index, moved by the answer, lies by its target index. The scan
// is shuffled (no NaN), so the indices are cloud positions, not bearing order.
TEST(ContourRegistration, TheVisualisationCallbackGetsTheCornerPairs) {
  const ScanPair pair;
  auto shuffled = pcl::make_shared<Cloud>(*finite(pair.source));
  std::mt19937 rng(3);
  std::shuffle(shuffled->begin(), shuffled->end(), rng);
  ContourRegistration<pcl::PointXYZ, pcl::PointXYZ> registration;
  registration.setInputSource(shuffled);
  registration.setInputTarget(pair.target);
  int calls = 0;
  pcl::Indices sources, targets;
  Cloud moved;
  std::function<void(const Cloud &, const pcl::Indices &, const Cloud &, const pcl::Indices &)> show =
      [&](const Cloud &source, const pcl::Indices &source_indices, const Cloud &, const pcl::Indices &target_indices) {
        ++calls;
        moved = source;
        sources = source_indices;
        targets = target_indices;
      };
  ASSERT_TRUE(registration.registerVisualizationCallback(show));
  calls = 0;  // PCL calls it once as it is registered
  Cloud aligned;
  registration.align(aligned);
  ASSERT_TRUE(registration.hasConverged()) << registration.getFailureReason();
  EXPECT_EQ(calls, 1);
  ASSERT_EQ(sources.size(), registration.getResult().inliers.size());
  ASSERT_EQ(targets.size(), sources.size());
  ASSERT_GE(sources.size(), 3u);
  for (std::size_t k = 0; k < sources.size(); ++k) {
    const pcl::PointXYZ &s = moved[sources[k]], &t = (*pair.target)[targets[k]];
    EXPECT_LT(std::hypot(s.x - t.x, s.y - t.y), 0.1) << k;
  }
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
    // PCL's contract, the same for every method: the output is the source moved by the answer.
    ASSERT_EQ(aligned.size(), source->size());
    const Eigen::Matrix4f t = method->getFinalTransformation();
    double worst = 0.0;
    for (std::size_t k = 0; k < source->size(); ++k)
      worst =
          std::max<double>(worst, (aligned[k].getVector3fMap() - (t * (*source)[k].getVector4fMap()).head<3>()).norm());
    EXPECT_LT(worst, 1e-4);
    if (name == "contour") {
      ASSERT_TRUE(method->hasConverged());
      EXPECT_LT(pair.translationError(method->getFinalTransformation()), 0.02);
    }
  }
}

// The odometry step: swap, set the next scan as source, align. Each scan's special points
// are extracted once: the target's are those extracted from it as the source of the step before.
// Two scans of the room by a 5 Hz LIDAR on a robot driving 1 m/s and turning 1 rad/s without
// stopping: each sweep spans 0.15 m and 9 deg. The truth maps the sensor at the source's first
// beam into the sensor at the target's.
TEST(ContourRegistration, ASweepDeskewsScansTakenWhileMoving) {
  const test::RoomWithBoxes room;
  const Twist2D twist{1.0, 0.0, 1.0};
  const double period = 0.2;
  simulation::LidarModel lidar = simulation::LidarModel::hokuyoUtm30lx();
  lidar.range_noise = 0.005;
  const double time_increment = beamInterval(period, lidar.angleIncrement());
  auto motion = [&](double t) {
    Complex position;
    double heading = 0.0;
    integrateTwist(twist, t, position, heading);
    return test::pose2d(position.real(), position.imag(), heading * 180.0 / M_PI);
  };
  std::mt19937 rng(7);
  const Eigen::Isometry2d start = test::pose2d(-2.0, -0.5, 10.0);
  auto swept = [&](const Eigen::Isometry2d &first_beam) {
    return simulation::simulateScan(
        room.world, [&](std::size_t n) { return first_beam * motion(time_increment * static_cast<double>(n)); }, lidar,
        rng);
  };
  const LaserScan target = swept(start), source = swept(start * motion(period));
  const Eigen::Isometry2d truth = motion(period);

  ContourRegistration<pcl::PointXYZ, pcl::PointXYZ> registration;
  registration.setInputTarget(odometry::beamCloud(target));
  registration.setInputSource(odometry::beamCloud(source));
  auto error = [&] {
    Cloud aligned;
    registration.align(aligned);
    const Eigen::Matrix4f found = registration.getFinalTransformation();
    const double yaw = std::atan2(found(1, 0), found(0, 0));
    const Eigen::Rotation2Dd true_turn(truth.linear());
    return std::make_pair(std::hypot(found(0, 3) - truth.translation().x(), found(1, 3) - truth.translation().y()),
                          std::abs(std::remainder(yaw - true_turn.angle(), 2 * M_PI)) * 180.0 / M_PI);
  };
  const auto raw = error();
  const bool raw_converged = registration.hasConverged();
  registration.setSourceSweep(Sweep{time_increment, twist});
  registration.setTargetSweep(Sweep{time_increment, twist});
  const auto deskewed = error();
  ASSERT_TRUE(registration.hasConverged()) << registration.getFailureReason();
  EXPECT_LT(deskewed.first, 0.003);  // m
  EXPECT_LT(deskewed.second, 0.1);   // deg
  // Indices that leave out the first third of the source's beams: each named point keeps the
  // time of its place in the sweep.
  auto later = pcl::make_shared<pcl::Indices>();
  for (std::size_t n = source.ranges.size() / 3; n < source.ranges.size(); ++n) later->push_back(static_cast<int>(n));
  registration.setIndices(later);
  const auto indexed = error();
  ASSERT_TRUE(registration.hasConverged()) << registration.getFailureReason();
  EXPECT_LT(indexed.first, 0.003);
  EXPECT_LT(indexed.second, 0.1);
  registration.setIndices(pcl::IndicesPtr());
  if (raw_converged) {
    EXPECT_GT(raw.second, 0.2);  // the bent scans turn the answer
  }
  // Back to scans taken at once: the same answer as before.
  registration.setSourceSweep(Sweep{});
  registration.setTargetSweep(Sweep{});
  EXPECT_EQ(error(), raw);
}

TEST(ContourRegistration, SwapReusesTheLastSourcesFeaturesAsTarget) {
  const simulation::World world = simulation::makeFurnishedRoom();
  ContourRegistration<pcl::PointXYZ, pcl::PointXYZ> registration;
  registration.setInputSource(odometry::beamCloud(test::scanFrom(world, test::pose2d(0, 0, 0), 0.01, 1)));
  std::uint64_t last_source_extraction = 0, last_extraction = 0;
  for (int k = 1; k <= 4; ++k) {
    SCOPED_TRACE(k);
    registration.swapSourceAndTarget();
    registration.setInputSource(
        odometry::beamCloud(test::scanFrom(world, test::pose2d(0.2 * k, 0.05 * k, 3 * k), 0.01, 1 + k)));
    Cloud aligned;
    registration.align(aligned);
    if (k > 1) {  // the first target had not been aligned as a source: this align() read it
      EXPECT_EQ(registration.getTargetFeatures().extraction, last_source_extraction);
      EXPECT_EQ(registration.getSourceFeatures().extraction, last_extraction + 1);  // one extraction a step
    }
    ASSERT_TRUE(registration.hasConverged()) << registration.getFailureReason();
    const Eigen::Matrix4f t = registration.getFinalTransformation();
    const Eigen::Isometry2d truth =
        test::pose2d(0.2 * (k - 1), 0.05 * (k - 1), 3 * (k - 1)).inverse() * test::pose2d(0.2 * k, 0.05 * k, 3 * k);
    EXPECT_LT((t.block<2, 1>(0, 3).cast<double>() - truth.translation()).norm(), 0.02);
    last_source_extraction = registration.getSourceFeatures().extraction;
    last_extraction = std::max(last_source_extraction, registration.getTargetFeatures().extraction);
  }
}

// PCL's own setters drive the settings they name.
TEST(ContourRegistration, PclSettersDriveTheSettingsTheyName) {
  const ScanPair pair;
  using Contour = ContourRegistration<pcl::PointXYZ, pcl::PointXYZ>;
  const auto run = [&](const std::function<void(Contour &)> &configure) {
    auto registration = pcl::make_shared<Contour>();
    configure(*registration);
    registration->setInputSource(pair.source);
    registration->setInputTarget(pair.target);
    Cloud aligned;
    registration->align(aligned);
    return registration;
  };
  const auto defaults = run([](Contour &) {});
  ASSERT_TRUE(defaults->hasConverged());
  EXPECT_EQ(defaults->getRegistrationParams().ransac.max_iterations, RegistrationParams{}.ransac.max_iterations);

  // RANSAC iterations: one hypothesis only.
  const auto one_hypothesis = run([](Contour &r) { r.setRANSACIterations(1); });
  EXPECT_EQ(one_hypothesis->getResult().ransac_iterations, 1);
  EXPECT_GT(defaults->getResult().ransac_iterations, 1);

  // RANSAC inlier threshold: 1 mm leaves fewer corners in agreement than 15 cm.
  const auto strict = run([](Contour &r) { r.setRANSACOutlierRejectionThreshold(0.001); });
  EXPECT_LT(strict->getResult().inliers.size(), defaults->getResult().inliers.size());

  // The refinement's pairing distance: 1 cm pairs less of the noisy contour than the default.
  const auto narrow = run([](Contour &r) { r.setMaxCorrespondenceDistance(0.01); });
  EXPECT_DOUBLE_EQ(narrow->getRegistrationParams().refinement.max_distance, 0.01);
  EXPECT_LT(narrow->getResult().overlap, defaults->getResult().overlap - 0.1);

  // The refinement's iterations: one step from the corners' answer fits the contours worse than twelve.
  const auto one_step = run([](Contour &r) { r.setMaximumIterations(1); });
  ASSERT_TRUE(one_step->hasConverged());
  EXPECT_GT(one_step->getResult().contour_rmse, defaults->getResult().contour_rmse);

  // The transformation epsilon: a 10 cm stop ends the refinement at the first step below it
  // that paired at the final distance (here the only one, 8 cm, from the first step on).
  const auto fixed_distance = run([](Contour &r) { r.setMaxCorrespondenceDistance(0.08); });
  const auto loose = run([](Contour &r) {
    r.setMaxCorrespondenceDistance(0.08);
    r.setTransformationEpsilon(0.1 * 0.1);
    r.setTransformationRotationEpsilon(std::cos(0.1));
  });
  EXPECT_DOUBLE_EQ(loose->getRegistrationParams().refinement.stop_translation, 0.1);
  EXPECT_NEAR(loose->getRegistrationParams().refinement.stop_rotation, 0.1, 1e-9);
  EXPECT_FALSE(loose->getFinalTransformation().isApprox(fixed_distance->getFinalTransformation(), 1e-7f));

  // Documented as having no effect: the Euclidean fitness epsilon.
  const auto fitness = run([](Contour &r) { r.setEuclideanFitnessEpsilon(1.0); });
  EXPECT_TRUE(fitness->getFinalTransformation().isApprox(defaults->getFinalTransformation()));

  // setRegistrationParams() and the PCL setters write the same settings: the last call holds.
  RegistrationParams params;
  params.ransac.max_iterations = 7;
  const auto last_call = run([&](Contour &r) {
    r.setRANSACIterations(3);
    r.setRegistrationParams(params);
  });
  EXPECT_EQ(last_call->getRegistrationParams().ransac.max_iterations, 7);
  EXPECT_LE(last_call->getResult().ransac_iterations, 7);
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
  registration.setInputTarget(odometry::beamCloud(test::scanFrom(corridor, test::pose2d(0, 0, 0), 0.01, 1)));
  registration.setInputSource(odometry::beamCloud(test::scanFrom(corridor, test::pose2d(0.4, 0, 2), 0.01, 2)));
  Cloud aligned;
  registration.align(aligned);
  EXPECT_FALSE(registration.hasConverged());
  EXPECT_NE(registration.getFailureReason().find("special points"), std::string::npos);
  // PCL's ICP, on the same pair, reports convergence although the corridor fixes nothing along its axis.
  pcl::IterativeClosestPoint<pcl::PointXYZ, pcl::PointXYZ> icp;
  icp.setInputSource(finite(odometry::beamCloud(test::scanFrom(corridor, test::pose2d(0.4, 0, 2), 0.01, 2))));
  icp.setInputTarget(finite(odometry::beamCloud(test::scanFrom(corridor, test::pose2d(0, 0, 0), 0.01, 1))));
  icp.align(aligned);
  EXPECT_TRUE(icp.hasConverged());
  EXPECT_GT(std::abs(icp.getFinalTransformation()(0, 3) - 0.4f), 0.1f);
}

}  // namespace
}  // namespace contour_reg
