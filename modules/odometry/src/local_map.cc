#include "contour_reg/odometry/local_map.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "contour_reg/io/pose2d.h"

namespace contour_reg::odometry {

LaserScan renderLocalMap(const std::vector<MapKeyframe> &keyframes) {
  LaserScan map;
  if (keyframes.empty() || !keyframes.back().scan) return map;
  const MapKeyframe &newest = keyframes.back();
  const LaserScan &own = *newest.scan;
  const double increment = std::abs(own.angle_increment);
  if (!(increment > 0.0)) return map;
  const auto beams = static_cast<std::size_t>(std::ceil(2.0 * M_PI / increment - 1e-9));
  map.stamp = own.stamp;
  map.angle_increment = increment;
  // Beam 0 at or just above -pi, on the grid of the newest scan's own bearings.
  map.angle_min = own.angle_min - increment * std::floor((own.angle_min + M_PI) / increment);
  map.range_min = own.range_min;
  map.range_max = own.range_max;
  map.ranges.assign(beams, std::numeric_limits<float>::quiet_NaN());

  // Newest first: a keyframe fills only the bearings the newer ones left empty.
  const auto turn_of_beams = static_cast<long>(beams);
  std::vector<float> ranges(beams);  // one keyframe's nearest return per bearing
  ComplexSequence code;
  for (auto k = keyframes.rbegin(); k != keyframes.rend(); ++k) {
    if (!k->scan) continue;
    const io::Pose2D seen = io::between(newest.pose, k->pose);
    const Complex turn = std::polar(1.0, seen.yaw), shift(seen.x, seen.y);
    std::fill(ranges.begin(), ranges.end(), std::numeric_limits<float>::quiet_NaN());
    deskewedPolarCode(*k->scan, k->motion, code);
    for (const Complex &point : code) {
      if (!isFinite(point)) continue;
      const Complex p = turn * point + shift;
      const double range = magnitude(p);
      if (!map.isValidRange(range)) continue;
      long bin = std::lround((std::arg(p) - map.angle_min) / increment) % turn_of_beams;
      if (bin < 0) bin += turn_of_beams;
      float &nearest = ranges[static_cast<std::size_t>(bin)];
      if (!(nearest <= range)) nearest = static_cast<float>(range);
    }
    for (std::size_t n = 0; n < beams; ++n)
      if (std::isnan(map.ranges[n]) && !std::isnan(ranges[n])) map.ranges[n] = ranges[n];
  }
  return map;
}

}  // namespace contour_reg::odometry
