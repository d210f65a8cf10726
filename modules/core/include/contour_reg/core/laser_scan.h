#pragma once
/// @file laser_scan.h
/// One 2-D LIDAR scan in the shape of sensor_msgs/LaserScan.

#include <cmath>
#include <vector>

namespace contour_reg {

/// One scan: ranges in beam order, beam n at bearing angle_min + n * angle_increment.
/// A range is valid when finite and inside [range_min, range_max); anything else
/// (NaN, inf, 0, negative, no-return readings at the maximum) marks an invalid beam.
struct LaserScan {
  double stamp = 0.0;            ///< seconds, when beam 0 was taken (sensor_msgs' convention)
  double angle_min = 0.0;        ///< rad, bearing of beam 0
  double angle_increment = 0.0;  ///< rad between consecutive beams
  double range_min = 0.0;        ///< m, readings below are invalid
  double range_max = 0.0;        ///< m, readings at or above are invalid (0: no limit)
  /// s between consecutive beams, as sensor_msgs/LaserScan's time_increment: beam n was taken
  /// at stamp + n * time_increment. 0: all at the stamp (a stopped robot, or unknown).
  double time_increment = 0.0;
  std::vector<float> ranges;  ///< m

  /// True when beam range r can be used.
  bool isValidRange(double r) const {
    return std::isfinite(r) && r > 0.0 && r >= range_min && (range_max <= 0.0 || r < range_max);
  }
  /// Bearing of beam n in rad.
  double bearing(std::size_t n) const { return angle_min + static_cast<double>(n) * angle_increment; }
};

/// s between consecutive beams of a LIDAR that turns once per `turn_period` s, beams
/// `angle_increment` rad apart (LaserScan::time_increment).
inline double beamInterval(double turn_period, double angle_increment) {
  return turn_period * std::abs(angle_increment) / (2.0 * M_PI);
}

}  // namespace contour_reg
