#include "contour_reg/evaluation/free_space_check.h"

#include <random>

#include <gtest/gtest.h>

#include "contour_reg/core/transform_estimation.h"
#include "contour_reg/simulation/lidar.h"
#include "scenes.h"

namespace contour_reg::evaluation {
namespace {

Eigen::Matrix3d secondInFirst(const Eigen::Isometry2d &first, const Eigen::Isometry2d &second) {
  Eigen::Matrix3d m = Eigen::Matrix3d::Identity();
  m.topLeftCorner<2, 2>() = (first.inverse() * second).linear();
  m.topRightCorner<2, 1>() = (first.inverse() * second).translation();
  return m;
}

Eigen::Matrix3d offBy(const Eigen::Matrix3d &motion, double dx, double dy) {
  Eigen::Matrix3d off = motion;
  off(0, 2) += dx;
  off(1, 2) += dy;
  return off;
}

TEST(FreeSpaceCheck, TheTrueMotionOfARoomIsHardlyContradictedAndAMotionAMetreOffIs) {
  const test::RoomWithBoxes room;
  std::mt19937 rng(3);
  const auto lidar = simulation::LidarModel::hokuyoUtm30lx();
  const Eigen::Isometry2d a = test::pose2d(0.0, 0.0, 0.0), b = test::pose2d(0.8, 0.3, 10.0);
  const FreeSpaceCheck check(simulation::simulateScan(room.world, a, lidar, rng),
                             simulation::simulateScan(room.world, b, lidar, rng));
  const Eigen::Matrix3d truth = secondInFirst(a, b);
  EXPECT_LT(check.contradictedShare(truth), 0.01);
  EXPECT_GT(check.contradictedShare(offBy(truth, 1.0, 0.0)), 0.1);
  EXPECT_GT(check.contradictedShare(offBy(truth, 0.0, -1.0)), 0.1);
  EXPECT_GT(check.contradictedShare(truth * rigidTransform(0.0, 0.0, 0.3)), 0.1);
}

TEST(FreeSpaceCheck, APersonWalkingThroughOneScanContradictsTheTrueMotionByLessThanATie) {
  test::RoomWithBoxes room, with_person;
  with_person.world.addCircle({3.0, 0.5}, 0.25);
  std::mt19937 rng(4);
  const auto lidar = simulation::LidarModel::hokuyoUtm30lx();
  const Eigen::Isometry2d a = test::pose2d(0.0, 0.0, 0.0), b = test::pose2d(0.5, 0.0, 0.0);
  const FreeSpaceCheck check(simulation::simulateScan(room.world, a, lidar, rng),
                             simulation::simulateScan(with_person.world, b, lidar, rng));
  const double share = check.contradictedShare(secondInFirst(a, b));
  EXPECT_GT(share, 0.0);  // the person stands where the first scan saw the far wall
  EXPECT_LT(share, kFreeSpaceShareTie);
}

TEST(FreeSpaceCheck, IsolatedReturnsCountAmongPostsWithNoWall) {
  // Posts 0.1 m across, 3-9 m away: one or two beams each, no contour segment between them.
  simulation::World posts;
  for (int i = -3; i <= 3; ++i)
    for (int j = 1; j <= 3; ++j) posts.addCircle({3.0 * j, 2.5 * i + 0.7 * j}, 0.05);
  std::mt19937 rng(5);
  simulation::LidarModel lidar = simulation::LidarModel::hokuyoUtm30lx();
  lidar.range_noise = 0.0;
  const Eigen::Isometry2d a = test::pose2d(0.0, 0.0, 0.0), b = test::pose2d(0.6, 0.2, 5.0);
  const FreeSpaceCheck check(simulation::simulateScan(posts, a, lidar, rng),
                             simulation::simulateScan(posts, b, lidar, rng));
  const Eigen::Matrix3d truth = secondInFirst(a, b);
  EXPECT_LT(check.contradictedShare(truth), 0.05);
  EXPECT_GT(check.contradictedShare(offBy(truth, 1.5, 0.0)), 0.3);
}

TEST(FreeSpaceCheck, ScansWithNoReturnsInEachOthersViewGiveNoEvidence) {
  LaserScan empty;
  empty.angle_min = -M_PI / 2;
  empty.angle_increment = M_PI / 180;
  empty.ranges.assign(181, std::numeric_limits<float>::quiet_NaN());
  const FreeSpaceCheck check(empty, empty);
  EXPECT_EQ(check.contradictedShare(Eigen::Matrix3d::Identity()), 0.0);
}

}  // namespace
}  // namespace contour_reg::evaluation
