#pragma once
// Scan pairs for the benchmarks: a furnished room seen by a 270-degree LIDAR of a given
// beam count, from two poses 0.15 m and 3 degrees apart (consecutive scans at 5-10 Hz).

#include <random>

#include <Eigen/Geometry>

#include "contour_reg/core/laser_scan.h"
#include "contour_reg/simulation/lidar.h"
#include "contour_reg/simulation/world.h"

namespace contour_reg::bench {

inline simulation::World furnishedRoom() {
  simulation::World world;
  world.addPolygon({{-6.0, -4.0}, {7.0, -4.0}, {7.0, 1.0}, {7.6, 1.0}, {7.6, 2.2}, {7.0, 2.2},
                    {7.0, 5.0}, {-2.0, 5.0}, {-2.0, 5.8}, {-3.0, 5.8}, {-3.0, 5.0}, {-6.0, 5.0}});
  world.addBox({-4.8, -3.2}, {-3.6, -2.4});
  world.addBox({2.0, 2.5}, {3.4, 3.3});
  world.addBox({4.2, -2.8}, {5.0, -1.6});
  world.addPolygon({{-2.5, 1.5}, {-1.9, 1.5}, {-1.9, 2.1}, {-2.5, 2.1}});
  world.addPolygon({{0.8, -1.8}, {1.6, -2.3}, {2.0, -1.7}});
  world.addCircle({-4.0, 3.0}, 0.3);
  return world;
}

struct ScanPair {
  LaserScan target, source;
  Eigen::Vector3d truth;  // x, y, yaw of the source in the target frame
};

inline ScanPair scanPair(int beams) {
  const simulation::World world = furnishedRoom();
  simulation::LidarModel model = simulation::LidarModel::hokuyoUtm30lx();
  model.beams = beams;
  std::mt19937 rng(7);
  Eigen::Isometry2d a = Eigen::Isometry2d::Identity(), b = Eigen::Isometry2d::Identity();
  b.translate(Eigen::Vector2d(0.15, 0.05));
  b.rotate(3.0 * M_PI / 180.0);
  return {simulation::simulateScan(world, a, model, rng), simulation::simulateScan(world, b, model, rng),
          {0.15, 0.05, 3.0 * M_PI / 180.0}};
}

}  // namespace contour_reg::bench
