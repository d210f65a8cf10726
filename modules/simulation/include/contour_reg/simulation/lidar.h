#pragma once
/// @file lidar.h
/// A simulated 2-D LIDAR: beam geometry, range limits, Gaussian range noise and dropout.

#include <functional>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "contour_reg/core/laser_scan.h"
#include "contour_reg/simulation/world.h"

namespace contour_reg::simulation {

struct LidarModel {
  std::string name = "custom";
  int beams = 1081;
  double field_of_view = 270.0 * M_PI / 180.0;  ///< rad, centred on the sensor's x axis
  double range_min = 0.1;                       ///< m
  double range_max = 30.0;                      ///< m; beyond it a beam returns no echo
  double range_noise = 0.01;                    ///< m, standard deviation of Gaussian range noise
  double dropout = 0.0;                         ///< probability that a beam returns no echo
  double range_resolution = 0.0;                ///< m, a range is reported rounded to this step (0: exactly)

  double angleIncrement() const { return beams > 1 ? field_of_view / (beams - 1) : 0.0; }

  /// Hokuyo UTM-30LX-like: 1081 beams over 270 deg, 30 m, 1 cm noise.
  static LidarModel hokuyoUtm30lx();
  /// YDLidar X4-like: 720 beams over 360 deg, 10 m, 2 cm noise, 1 % dropout.
  static LidarModel ydlidarX4();
  /// SICK LMS200-like, as in the CARMEN logs: 181 beams over 180 deg (1 deg apart), 80 m,
  /// 1 cm noise, ranges reported in whole centimetres.
  static LidarModel sickLms200();
};

/// The LIDAR models the command line and Python name: hokuyo (hokuyoUtm30lx), ydlidar
/// (ydlidarX4), sick (sickLms200); the model of a name, none for another name.
const std::vector<std::string> &lidarModelNames();
std::optional<LidarModel> lidarModelNamed(const std::string &name);

/// Simulates one scan from `pose` (sensor frame in the world). A beam with no echo
/// reads NaN. `rng` drives noise and dropout; a fixed seed fixes the scan.
LaserScan simulateScan(const World &world, const Eigen::Isometry2d &pose, const LidarModel &model, std::mt19937 &rng);

/// Simulates one scan taken while moving: beam n is cast from `pose_of_beam(n)`, the sensor
/// pose at the moment that beam fires, so the scan is distorted as a real one is.
LaserScan simulateScan(const World &world, const std::function<Eigen::Isometry2d(std::size_t)> &pose_of_beam,
                       const LidarModel &model, std::mt19937 &rng);

}  // namespace contour_reg::simulation
