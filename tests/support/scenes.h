#pragma once
// Test scenes with known geometry, built on the simulation module.

#include <cmath>
#include <random>
#include <vector>

#include <Eigen/Geometry>

#include "contour_reg/core/laser_scan.h"
#include "contour_reg/simulation/lidar.h"
#include "contour_reg/simulation/office.h"
#include "contour_reg/simulation/world.h"

namespace contour_reg::test {

inline Eigen::Isometry2d pose2d(double x, double y, double yaw_deg) {
  Eigen::Isometry2d pose = Eigen::Isometry2d::Identity();
  pose.translate(Eigen::Vector2d(x, y));
  pose.rotate(yaw_deg * M_PI / 180.0);
  return pose;
}

/// A 11 m x 7 m room with two boxes: every corner is a 90-degree corner.
struct RoomWithBoxes {
  simulation::World world;
  std::vector<Eigen::Vector2d> corners;  // world frame, all of them

  RoomWithBoxes() {
    world.addBox({-5.0, -3.0}, {6.0, 4.0});
    world.addBox({-1.5, -2.2}, {-0.5, -1.2});
    world.addBox({1.0, 2.0}, {2.0, 3.0});
    corners = {{-5.0, -3.0}, {6.0, -3.0},  {6.0, 4.0}, {-5.0, 4.0}, {-1.5, -2.2}, {-0.5, -2.2},
               {-0.5, -1.2}, {-1.5, -1.2}, {1.0, 2.0}, {2.0, 2.0},  {2.0, 3.0},   {1.0, 3.0}};
  }

  /// The corners a 270-degree sensor at `pose` sees as corners, in the sensor frame: inside
  /// the field of view (with a margin), in line of sight, and not a silhouette edge (the
  /// surface continues on both sides of the corner's bearing).
  std::vector<Eigen::Vector2d> visibleCorners(const Eigen::Isometry2d &pose) const {
    std::vector<Eigen::Vector2d> visible;
    const double heading = std::atan2(pose.linear()(1, 0), pose.linear()(0, 0));
    for (const Eigen::Vector2d &corner : corners) {
      const Eigen::Vector2d local = pose.inverse() * corner;
      const double bearing = std::atan2(local.y(), local.x()), distance = local.norm();
      if (std::abs(bearing) > 130.0 * M_PI / 180.0) continue;
      bool seen = true;
      for (double side : {-0.02, 0.0, 0.02}) {
        const double a = heading + bearing + side;
        const double hit = world.castRay(pose.translation(), {std::cos(a), std::sin(a)});
        if (std::abs(hit - distance) > (side == 0.0 ? 0.01 : 0.3)) seen = false;
      }
      if (seen) visible.push_back(local);
    }
    return visible;
  }
};

/// Two parallel walls 2.5 m apart (y -1.2 and 1.3) from x -half_length to half_length, nothing else.
inline simulation::World bareCorridor(double half_length) {
  simulation::World corridor;
  corridor.addSegment({-half_length, -1.2}, {half_length, -1.2});
  corridor.addSegment({-half_length, 1.3}, {half_length, 1.3});
  return corridor;
}

/// A corridor 2.5 m wide with a door recess every 3 m along one wall, closed 9 m ahead of the origin.
inline simulation::World corridorOfDoors() {
  simulation::World corridor;
  corridor.addSegment({-15.0, 1.3}, {9.0, 1.3});
  corridor.addSegment({9.0, 1.3}, {9.0, -1.2});
  for (double x = -15.0; x < 9.0; x += 3.0) {
    corridor.addSegment({x, -1.2}, {x + 2.1, -1.2});
    corridor.addSegment({x + 2.1, -1.2}, {x + 2.1, -1.4});
    corridor.addSegment({x + 2.1, -1.4}, {x + 3.0, -1.4});
    corridor.addSegment({x + 3.0, -1.4}, {x + 3.0, -1.2});
  }
  return corridor;
}

/// A corridor 3 m wide closed at x = 9 m, its right wall a row of teeth 1.4 m apart (a wall
/// of shallow bays, as in a convention centre): every tooth tip is a corner like the next.
inline simulation::World sawtoothCorridor() {
  simulation::World corridor;
  corridor.addSegment({-15.0, 1.5}, {9.0, 1.5});
  corridor.addSegment({9.0, 1.5}, {9.0, -1.5});
  for (double x = -15.0; x < 9.0; x += 1.4) {
    corridor.addSegment({x, -1.5}, {x + 1.0, -1.2});
    corridor.addSegment({x + 1.0, -1.2}, {x + 1.4, -1.5});
  }
  return corridor;
}

inline LaserScan scanFrom(const simulation::World &world, const Eigen::Isometry2d &pose, double noise = 0.0,
                          unsigned seed = 42) {
  simulation::LidarModel model = simulation::LidarModel::hokuyoUtm30lx();
  model.range_noise = noise;
  std::mt19937 rng(seed);
  return simulation::simulateScan(world, pose, model, rng);
}

}  // namespace contour_reg::test
