#include "contour_reg/point_to_line_icp.h"

#include <cmath>

#include <gtest/gtest.h>
#include <pcl/console/print.h>
#include <pcl/registration/icp.h>
#include <pcl/registration/transformation_estimation_2D.h>

#include "contour_reg/core/contour.h"
#include "contour_reg/odometry/scan_matcher.h"
#include "contour_reg/transformation_estimation_point_to_line_2d.h"
#include "scenes.h"

namespace contour_reg {
namespace {

using Cloud = pcl::PointCloud<pcl::PointXYZ>;
using PlIcp = PointToLineIcp<pcl::PointXYZ, pcl::PointXYZ>;

TEST(TransformationEstimationPointToLine2D, SolvesATranslationOntoTwoWallsExactly) {
  // Points on the walls x = 2 and y = 3, their normals; the source is the target moved by -t.
  pcl::PointCloud<pcl::PointNormal> target, source;
  const Eigen::Vector2d t(0.12, -0.07);
  for (int k = 0; k < 20; ++k) {
    pcl::PointNormal a, b;
    a.x = 2.f, a.y = -1.f + 0.1f * float(k), a.z = 0.f, a.normal_x = 1.f, a.normal_y = 0.f, a.normal_z = 0.f;
    b.x = -1.f + 0.1f * float(k), b.y = 3.f, b.z = 0.f, b.normal_x = 0.f, b.normal_y = 1.f, b.normal_z = 0.f;
    for (const pcl::PointNormal &q : {a, b}) {
      target.push_back(q);
      pcl::PointNormal p = q;
      p.x -= float(t.x());
      p.y -= float(t.y());
      source.push_back(p);
    }
  }
  TransformationEstimationPointToLine2D<pcl::PointNormal, pcl::PointNormal> estimation;
  Eigen::Matrix4f transform;
  estimation.estimateRigidTransformation(source, target, transform);
  EXPECT_NEAR(transform(0, 3), t.x(), 1e-5);
  EXPECT_NEAR(transform(1, 3), t.y(), 1e-5);
  EXPECT_NEAR(transform(1, 0), 0.0, 1e-5);
}

TEST(TransformationEstimationPointToLine2D, LeavesADirectionNoLineConstrainsAlone) {
  // One wall y = 3: the motion along it is unobservable and stays 0; across it, it is solved.
  pcl::PointCloud<pcl::PointNormal> target, source;
  for (int k = 0; k < 20; ++k) {
    pcl::PointNormal q;
    q.x = -1.f + 0.1f * float(k), q.y = 3.f, q.z = 0.f, q.normal_x = 0.f, q.normal_y = 1.f, q.normal_z = 0.f;
    target.push_back(q);
    q.x -= 0.3f;
    q.y -= 0.05f;
    source.push_back(q);
  }
  TransformationEstimationPointToLine2D<pcl::PointNormal, pcl::PointNormal> estimation;
  Eigen::Matrix4f transform;
  estimation.estimateRigidTransformation(source, target, transform);
  ASSERT_TRUE(transform.allFinite());
  EXPECT_NEAR(transform(1, 3), 0.05, 1e-4);
  EXPECT_NEAR(transform(0, 3), 0.0, 1e-3);
}

TEST(PointToLineIcp, RecoversASimulatedMotionInAFurnishedRoom) {
  const simulation::World world = simulation::makeFurnishedRoom();
  const Eigen::Isometry2d start = test::pose2d(0.5, -0.4, 20), motion = test::pose2d(0.2, -0.1, 6);
  PlIcp registration;
  registration.setInputTarget(odometry::beamCloud(test::scanFrom(world, start, 0.01, 1)));
  registration.setInputSource(odometry::beamCloud(test::scanFrom(world, start * motion, 0.01, 2)));
  Cloud aligned;
  registration.align(aligned);
  ASSERT_TRUE(registration.hasConverged());
  const Eigen::Matrix4f m = registration.getFinalTransformation();
  EXPECT_NEAR(m(0, 3), motion.translation().x(), 0.01);
  EXPECT_NEAR(m(1, 3), motion.translation().y(), 0.01);
  EXPECT_NEAR(std::atan2(m(1, 0), m(0, 0)), 6 * M_PI / 180, 0.3 * M_PI / 180);
  EXPECT_EQ(aligned.size(), registration.getInputSource()->size());
}

TEST(PointToLineIcp, ConvergesFromFartherThanPointToPointIcpInTheSameRoom) {
  // Point-to-line ICP slides along walls where point-to-point ICP is held by the spacing of
  // the points: from a 0.4 m, 10 deg start, on the same scans and settings.
  const auto verbosity = pcl::console::getVerbosityLevel();
  pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
  const simulation::World world = simulation::makeFurnishedRoom();
  const Eigen::Isometry2d start = test::pose2d(0.5, -0.4, 20), motion = test::pose2d(0.4, 0.2, 10);
  const auto target = odometry::beamCloud(test::scanFrom(world, start, 0.01, 1));
  const auto source = odometry::beamCloud(test::scanFrom(world, start * motion, 0.01, 2));
  auto error = [&](pcl::Registration<pcl::PointXYZ, pcl::PointXYZ> &registration) {
    registration.setMaxCorrespondenceDistance(1.0);
    registration.setMaximumIterations(50);
    registration.setInputTarget(target);
    registration.setInputSource(source);
    Cloud aligned;
    registration.align(aligned);
    const Eigen::Matrix4f m = registration.getFinalTransformation();
    return std::hypot(m(0, 3) - motion.translation().x(), m(1, 3) - motion.translation().y());
  };
  PlIcp point_to_line;
  pcl::IterativeClosestPoint<pcl::PointXYZ, pcl::PointXYZ> point_to_point;
  point_to_point.setTransformationEstimation(
      pcl::make_shared<pcl::registration::TransformationEstimation2D<pcl::PointXYZ, pcl::PointXYZ>>());
  EXPECT_LT(error(point_to_line), 0.02);
  EXPECT_GT(error(point_to_point), 0.03);  // 6 cm off: stopped by the point spacing
  pcl::console::setVerbosityLevel(verbosity);
}

TEST(PointToLineIcp, TooFewPointsIsNotConvergedAndKeepsTheGuess) {
  auto few = pcl::make_shared<Cloud>();
  few->push_back(pcl::PointXYZ(1.f, 0.f, 0.f));
  few->push_back(pcl::PointXYZ(std::nanf(""), std::nanf(""), 0.f));
  few->push_back(pcl::PointXYZ(1.f, 0.1f, 0.f));
  PlIcp registration;
  registration.setInputTarget(few);
  registration.setInputSource(few);
  Eigen::Matrix4f guess = Eigen::Matrix4f::Identity();
  guess(0, 3) = 0.5f;
  Cloud aligned;
  registration.align(aligned, guess);
  EXPECT_FALSE(registration.hasConverged());
  EXPECT_TRUE(registration.getFinalTransformation().isApprox(guess));
}

}  // namespace
}  // namespace contour_reg
