#pragma once
// Scan pairs for the benchmarks: a furnished room seen by a 270-degree LIDAR of a given
// beam count, from two poses 0.15 m and 3 degrees apart (consecutive scans at 5-10 Hz).

#include <random>

#include <Eigen/Geometry>

#include "contour_reg/core/laser_scan.h"
#include "contour_reg/simulation/lidar.h"
#include "contour_reg/simulation/office.h"
#include "contour_reg/simulation/world.h"

namespace contour_reg::bench {

struct ScanPair {
  LaserScan target, source;
  Eigen::Vector3d truth;  // x, y, yaw of the source in the target frame
};

inline ScanPair scanPair(int beams) {
  const simulation::World world = simulation::makeFurnishedRoom();
  simulation::LidarModel model = simulation::LidarModel::hokuyoUtm30lx();
  model.beams = beams;
  std::mt19937 rng(7);
  Eigen::Isometry2d a = Eigen::Isometry2d::Identity(), b = Eigen::Isometry2d::Identity();
  b.translate(Eigen::Vector2d(0.15, 0.05));
  b.rotate(3.0 * M_PI / 180.0);
  return {simulation::simulateScan(world, a, model, rng),
          simulation::simulateScan(world, b, model, rng),
          {0.15, 0.05, 3.0 * M_PI / 180.0}};
}

}  // namespace contour_reg::bench
