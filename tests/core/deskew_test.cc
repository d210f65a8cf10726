#include "contour_reg/core/deskew.h"

#include <algorithm>
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "contour_reg/simulation/lidar.h"
#include "scenes.h"

namespace contour_reg {
namespace {

// A wall along y = 3 m, seen by a 10 Hz LIDAR on a robot driving 1 m/s, drifting left and
// turning 0.8 rad/s: one revolution spans 0.1 m and 4.6 deg.
struct MovingScan {
  LaserScan scan;
  Twist2D twist{1.0, 0.2, 0.8};
};

MovingScan wallSeenWhileMoving() {
  simulation::World wall;
  wall.addSegment({-30.0, 3.0}, {30.0, 3.0});
  simulation::LidarModel model = simulation::LidarModel::hokuyoUtm30lx();
  model.range_noise = 0.0;
  MovingScan moving;
  const double time_increment = beamInterval(0.1, model.angleIncrement());
  std::mt19937 rng(1);
  moving.scan = simulation::simulateScan(
      wall,
      [&](std::size_t n) {
        Complex position;
        double heading = 0.0;
        integrateTwist(moving.twist, time_increment * static_cast<double>(n), position, heading);
        return test::pose2d(position.real(), position.imag(), heading * 180.0 / M_PI);
      },
      model, rng);
  moving.scan.time_increment = time_increment;
  return moving;
}

// The largest distance of a code's points from the line y = 3.
double offWall(const ComplexSequence &code) {
  double worst = 0.0;
  for (const Complex &c : code)
    if (isFinite(c)) worst = std::max(worst, std::abs(c.imag() - 3.0));
  return worst;
}

TEST(Deskew, AStraightWallSeenWhileMovingAndTurningComesOutStraight) {
  const MovingScan moving = wallSeenWhileMoving();
  const ComplexSequence raw = polarCode(moving.scan);
  const ComplexSequence deskewed = deskewedPolarCode(moving.scan, moving.twist);
  EXPECT_GT(offWall(raw), 0.1);  // bent by the motion
  EXPECT_LT(offWall(deskewed), 1e-6);
}

TEST(Deskew, ZeroMotionOrNoBeamTimingChangesNothing) {
  MovingScan moving = wallSeenWhileMoving();
  const ComplexSequence raw = polarCode(moving.scan);
  auto same = [&](const ComplexSequence &code) {
    ASSERT_EQ(code.size(), raw.size());
    for (std::size_t n = 0; n < raw.size(); ++n) {
      if (isFinite(raw[n])) {
        EXPECT_EQ(code[n], raw[n]) << n;
      }
    }
  };
  same(deskewedPolarCode(moving.scan, Twist2D{}));
  moving.scan.time_increment = 0.0;  // a stopped scan, or one without timing
  same(deskewedPolarCode(moving.scan, moving.twist));
}

TEST(Deskew, TheTwistIntegratesAlongAnArc) {
  Complex position;
  double heading = 0.0;
  integrateTwist(Twist2D{1.0, 0.0, M_PI / 2}, 1.0, position, heading);  // a quarter circle of radius 2/pi
  EXPECT_NEAR(heading, M_PI / 2, 1e-12);
  EXPECT_NEAR(position.real(), 2.0 / M_PI, 1e-12);
  EXPECT_NEAR(position.imag(), 2.0 / M_PI, 1e-12);
  integrateTwist(Twist2D{1.0, 0.5, 0.0}, 2.0, position, heading);  // straight
  EXPECT_NEAR(position.real(), 2.0, 1e-12);
  EXPECT_NEAR(position.imag(), 1.0, 1e-12);
}

// A robot that drives straight for the first half of a 1 Hz LIDAR's sweep and turns at 1 rad/s
// for the rest, as at the start of a corner: no constant twist describes its sweep.
TEST(Deskew, AMotionThatChangesDuringTheSweepIsFollowedPieceByPiece) {
  simulation::World wall;
  wall.addSegment({-30.0, 3.0}, {30.0, 3.0});
  simulation::LidarModel model = simulation::LidarModel::hokuyoUtm30lx();
  model.range_noise = 0.0;
  const double time_increment = beamInterval(1.0, model.angleIncrement()), half = 0.375;
  const Twist2D straight{0.5, 0.0, 0.0}, turning{0.5, 0.0, 1.0};
  const SweepMotion motion(straight, {{half, turning}});
  std::mt19937 rng(1);
  LaserScan scan = simulation::simulateScan(
      wall,
      [&](std::size_t n) {
        const double t = time_increment * static_cast<double>(n);
        Complex position, turned;
        double heading = 0.0, after = 0.0;
        integrateTwist(straight, std::min(t, half), position, heading);
        integrateTwist(turning, std::max(t - half, 0.0), turned, after);
        position += std::polar(1.0, heading) * turned;
        return test::pose2d(position.real(), position.imag(), (heading + after) * 180.0 / M_PI);
      },
      model, rng);
  scan.time_increment = time_increment;
  // The same net motion over the sweep as one constant twist, as odometry sampled once per scan gives it.
  const double sweep = time_increment * static_cast<double>(scan.ranges.size());
  const Twist2D mean{0.5, 0.0, (sweep - half) / sweep};
  EXPECT_LT(offWall(deskewedPolarCode(scan, motion)), 1e-6);
  EXPECT_GT(offWall(deskewedPolarCode(scan, mean)), 0.05);
  // A change to the same twist changes nothing.
  const ComplexSequence constant = deskewedPolarCode(scan, turning),
                        split = deskewedPolarCode(scan, SweepMotion(turning, {{half, turning}}));
  for (std::size_t n = 0; n < constant.size(); ++n)
    if (isFinite(constant[n])) EXPECT_LT(std::abs(constant[n] - split[n]), 1e-9) << n;
}

}  // namespace
}  // namespace contour_reg
