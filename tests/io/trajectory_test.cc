#include <cmath>

#include <gtest/gtest.h>

#include "contour_reg/io/pose2d.h"
#include "contour_reg/io/trajectory.h"
#include "temp_dir.h"

namespace contour_reg::io {
namespace {

TEST(Tum, WrittenTrajectoriesReadBack) {
  test::TempDir dir;
  const Trajectory written{{1.5, {1.0, 2.0, 0.5}}, {2.5, {-3.0, 4.0, -3.0}}};
  writeTum(dir.file("t.tum"), written);
  const Trajectory read = readTum(dir.file("t.tum"));
  ASSERT_EQ(read.size(), 2u);
  EXPECT_NEAR(read[1].stamp, 2.5, 1e-9);
  EXPECT_NEAR(read[1].pose.x, -3.0, 1e-6);
  EXPECT_NEAR(read[1].pose.yaw, -3.0, 1e-6);
  EXPECT_NEAR(read[0].pose.yaw, 0.5, 1e-6);
}

TEST(Tum, ATrajectoryIsReadInStampOrder) {
  // Trajectories appended from several runs, or merged by hand, need not be in stamp order;
  // poses are looked up by stamp (evaluation::poseAt bisects them).
  test::TempDir dir;
  const auto path = dir.write("t.tum", "3 3 0 0 0 0 0 1\n1 1 0 0 0 0 0 1\n2 2 0 0 0 0 0 1\n");
  const Trajectory read = readTum(path);
  ASSERT_EQ(read.size(), 3u);
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_DOUBLE_EQ(read[k].stamp, static_cast<double>(k + 1));
    EXPECT_DOUBLE_EQ(read[k].pose.x, static_cast<double>(k + 1));
  }
}

TEST(Tum, ABadLineIsAnErrorNamingFileAndLine) {
  test::TempDir dir;
  const auto path = dir.write("t.tum", "# header\n1 0 0 0 0 0 0 1\n2 0 0 0 zero 0 0 1\n");
  try {
    readTum(path);
    FAIL();
  } catch (const ReadError &error) {
    EXPECT_NE(std::string(error.what()).find(path + ":3"), std::string::npos) << error.what();
  }
}

// A quaternion is the rotation of its unit quaternion, whatever its norm (a file written by
// hand, or with few digits); one of norm zero is no rotation, an error naming file and line.
TEST(Tum, AQuaternionIsTheRotationOfItsUnitQuaternion) {
  test::TempDir dir;
  const Trajectory read = readTum(dir.write("t.tum", "1 0 0 0 0 0 10 10\n2 0 0 0 0 0 -0.5 0.5\n3 0 0 0 0 0 0 2\n"));
  ASSERT_EQ(read.size(), 3u);
  EXPECT_NEAR(read[0].pose.yaw, M_PI / 2, 1e-12);
  EXPECT_NEAR(read[1].pose.yaw, -M_PI / 2, 1e-12);
  EXPECT_NEAR(read[2].pose.yaw, 0.0, 1e-12);
  const auto path = dir.write("zero.tum", "1 0 0 0 0 0 0 1\n2 0 0 0 0 0 0 0\n");
  try {
    readTum(path);
    FAIL() << "a quaternion of norm zero was read";
  } catch (const ReadError &error) {
    EXPECT_NE(std::string(error.what()).find(path + ":2"), std::string::npos) << error.what();
  }
}

TEST(Relations, MotionIsTheSecondPoseInTheFrameOfTheFirst) {
  test::TempDir dir;
  const auto relations = readRelations(dir.write("r.relations", "10.5 12.0 0.3 -0.1 0 0 0 0.25\n"));
  ASSERT_EQ(relations.size(), 1u);
  EXPECT_DOUBLE_EQ(relations[0].t1, 10.5);
  EXPECT_DOUBLE_EQ(relations[0].t2, 12.0);
  EXPECT_DOUBLE_EQ(relations[0].motion.x, 0.3);
  EXPECT_DOUBLE_EQ(relations[0].motion.yaw, 0.25);
}

}  // namespace
}  // namespace contour_reg::io

namespace contour_reg::io {
namespace {

// The robot's motion from the laser's and back; the covariance carried by the Jacobian of the
// change, checked against finite differences.
TEST(Mounting, RobotAndLaserMotionsAreOneChangeOfFrameAndItsCovarianceFollows) {
  const Pose2D mounting{0.3, 0.1, 0.5}, laser{0.4, -0.2, 0.35};
  const Pose2D robot = robotMotion(laser, mounting), back = laserMotion(robot, mounting);
  EXPECT_NEAR(back.x, laser.x, 1e-12);
  EXPECT_NEAR(back.y, laser.y, 1e-12);
  EXPECT_NEAR(back.yaw, laser.yaw, 1e-12);
  EXPECT_NEAR(robot.yaw, laser.yaw, 1e-12);  // a turn is a turn in either frame
  // A turn in place of the laser moves the robot's centre: the laser 0.3 m ahead turning 90 deg.
  const Pose2D spin = robotMotion({0.0, 0.0, M_PI / 2}, {0.3, 0.0, 0.0});
  EXPECT_NEAR(spin.x, 0.3, 1e-12);
  EXPECT_NEAR(spin.y, -0.3, 1e-12);
  Eigen::Matrix3d numeric;
  const double h = 1e-6;
  for (int k = 0; k < 3; ++k) {
    Pose2D plus = laser, minus = laser;
    (k == 0 ? plus.x : k == 1 ? plus.y : plus.yaw) += h;
    (k == 0 ? minus.x : k == 1 ? minus.y : minus.yaw) -= h;
    const Pose2D a = robotMotion(plus, mounting), b = robotMotion(minus, mounting);
    numeric.col(k) = Eigen::Vector3d(a.x - b.x, a.y - b.y, a.yaw - b.yaw) / (2 * h);
  }
  const Eigen::Matrix3d covariance = Eigen::Vector3d(4e-4, 1e-4, 3e-5).asDiagonal();
  const Eigen::Matrix3d expected = numeric * covariance * numeric.transpose();
  EXPECT_LT((robotCovariance(covariance, laser, mounting) - expected).norm(), 1e-9);
}

}  // namespace
}  // namespace contour_reg::io
