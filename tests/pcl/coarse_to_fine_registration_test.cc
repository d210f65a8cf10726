#include "contour_reg/coarse_to_fine_registration.h"

#include <cmath>

#include <gtest/gtest.h>
#include <pcl/console/print.h>

#include "contour_reg/odometry/scan_matcher.h"
#include "scenes.h"

namespace contour_reg {
namespace {

using Cloud = pcl::PointCloud<pcl::PointXYZ>;
using CoarseToFine = CoarseToFineRegistration<pcl::PointXYZ, pcl::PointXYZ>;

TEST(CoarseToFineRegistration, TheFineStageStartsFromTheCoarseAnswer) {
  const simulation::World world = simulation::makeFurnishedRoom();
  const Eigen::Isometry2d motion = test::pose2d(0.35, -0.15, 12);
  CoarseToFine registration;
  registration.setInputTarget(odometry::beamCloud(test::scanFrom(world, test::pose2d(0.5, -0.4, 20), 0.01, 1)));
  registration.setInputSource(
      odometry::beamCloud(test::scanFrom(world, test::pose2d(0.5, -0.4, 20) * motion, 0.01, 2)));
  Cloud aligned;
  registration.align(aligned);
  ASSERT_TRUE(registration.hasConverged());
  EXPECT_FALSE(registration.fineFromGuess());
  EXPECT_FALSE(registration.fineStageRejected());
  // The coarse stage is reached without a cast, and the fine stage moved its answer only a little.
  ASSERT_TRUE(registration.getCoarseStage()->hasConverged());
  const Eigen::Matrix4f coarse = registration.getCoarseStage()->getFinalTransformation();
  const Eigen::Matrix4f fine = registration.getFinalTransformation();
  EXPECT_LT((coarse.block<2, 1>(0, 3) - fine.block<2, 1>(0, 3)).norm(), 0.02f);
  EXPECT_NEAR(fine(0, 3), motion.translation().x(), 0.02);
  EXPECT_NEAR(fine(1, 3), motion.translation().y(), 0.02);
  EXPECT_EQ(aligned.size(), registration.getInputSource()->size());
}

TEST(CoarseToFineRegistration, UndecidedCornersLeaveTheAnswerToTheFineStageFromTheGuess) {
  const auto verbosity = pcl::console::getVerbosityLevel();
  pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
  simulation::World corridor;  // no corner, and the contours leave the axis free
  corridor.addSegment({-30, -1.2}, {30, -1.2});
  corridor.addSegment({-30, 1.3}, {30, 1.3});
  const auto target = odometry::beamCloud(test::scanFrom(corridor, test::pose2d(0, 0, 0), 0.01, 1));
  const auto source = odometry::beamCloud(test::scanFrom(corridor, test::pose2d(0.1, 0.05, 1), 0.01, 2));
  CoarseToFine registration;
  registration.setInputTarget(target);
  registration.setInputSource(source);
  Cloud aligned;
  registration.align(aligned);
  EXPECT_EQ(registration.getCoarseStage()->getResult().status, RegistrationStatus::kUnconstrained);
  EXPECT_TRUE(registration.fineFromGuess());
  EXPECT_TRUE(registration.hasConverged());  // ICP's own word, from the guess: right across the corridor
  EXPECT_NEAR(registration.getFinalTransformation()(1, 3), 0.05, 0.02);

  registration.setFineFromGuess(false);
  registration.align(aligned);
  EXPECT_FALSE(registration.fineFromGuess());
  EXPECT_FALSE(registration.hasConverged());
  EXPECT_TRUE(registration.getFinalTransformation().isIdentity());  // the guess
  pcl::console::setVerbosityLevel(verbosity);
}

// A guess the fine stage cannot start from (not finite, or moving the source beyond what single
// precision resolves) is not tried: PCL's ICP stops the process on a NaN guess (its kd-tree
// asserts) and "converges" somewhere from a far one. The coarse stage's verdict stands.
TEST(CoarseToFineRegistration, AGuessTheFineStageCannotStartFromIsNotTried) {
  const auto verbosity = pcl::console::getVerbosityLevel();
  pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
  simulation::World corridor;
  corridor.addSegment({-30, -1.2}, {30, -1.2});
  corridor.addSegment({-30, 1.3}, {30, 1.3});
  const auto target = odometry::beamCloud(test::scanFrom(corridor, test::pose2d(0, 0, 0), 0.01, 1));
  const auto source = odometry::beamCloud(test::scanFrom(corridor, test::pose2d(0.1, 0.05, 1), 0.01, 2));
  for (const float far : {NAN, INFINITY, 1e30f, 2e4f}) {
    SCOPED_TRACE(far);
    CoarseToFine registration;
    registration.setInputTarget(target);
    registration.setInputSource(source);
    Eigen::Matrix4f guess = Eigen::Matrix4f::Identity();
    guess(0, 3) = far;
    Cloud aligned;
    registration.align(aligned, guess);
    EXPECT_TRUE(isUndecided(registration.getCoarseStage()->getResult().status));
    EXPECT_FALSE(registration.fineFromGuess());
    EXPECT_FALSE(registration.hasConverged());
  }
  pcl::console::setVerbosityLevel(verbosity);
}

TEST(CoarseToFineRegistration, AFineCorrectionBeyondTheLimitKeepsTheCoarseAnswer) {
  const simulation::World world = simulation::makeFurnishedRoom();
  CoarseToFine registration;
  registration.setMaxFineCorrection(0.0, 0.0);  // any move of the fine stage is too far
  registration.setInputTarget(odometry::beamCloud(test::scanFrom(world, test::pose2d(0.5, -0.4, 20), 0.01, 1)));
  registration.setInputSource(odometry::beamCloud(test::scanFrom(world, test::pose2d(0.7, -0.3, 25), 0.01, 2)));
  Cloud aligned;
  registration.align(aligned);
  ASSERT_TRUE(registration.hasConverged());
  EXPECT_TRUE(registration.fineStageRejected());
  EXPECT_TRUE(registration.getFinalTransformation().isApprox(registration.getCoarseStage()->getFinalTransformation()));
}

// The stages are configured through getCoarseStage() and getFineStage(); the class's own PCL
// setters are documented as having no effect.
TEST(CoarseToFineRegistration, ItsOwnPclSettersHaveNoEffect) {
  const simulation::World world = simulation::makeFurnishedRoom();
  const auto target = odometry::beamCloud(test::scanFrom(world, test::pose2d(0.5, -0.4, 20), 0.01, 1));
  const auto source = odometry::beamCloud(test::scanFrom(world, test::pose2d(0.7, -0.3, 25), 0.01, 2));
  Cloud aligned;
  CoarseToFine plain, configured;
  configured.setMaximumIterations(1);
  configured.setRANSACIterations(1);
  configured.setRANSACOutlierRejectionThreshold(0.001);
  configured.setMaxCorrespondenceDistance(0.001);
  configured.setTransformationEpsilon(1.0);
  for (CoarseToFine *registration : {&plain, &configured}) {
    registration->setInputTarget(target);
    registration->setInputSource(source);
    registration->align(aligned);
    ASSERT_TRUE(registration->hasConverged());
  }
  EXPECT_TRUE(configured.getFinalTransformation().isApprox(plain.getFinalTransformation()));
  // ... while the coarse stage's own setter does what it names.
  configured.getCoarseStage()->setRANSACIterations(1);
  configured.align(aligned);
  EXPECT_EQ(configured.getCoarseStage()->getResult().ransac_iterations, 1);
}

}  // namespace
}  // namespace contour_reg
