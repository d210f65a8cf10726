#include "contour_reg/odometry/local_map.h"

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
  for (auto k = keyframes.rbegin(); k != keyframes.rend(); ++k) {
    if (!k->scan) continue;
    const io::Pose2D seen = io::between(newest.pose, k->pose);
    const Complex turn = std::polar(1.0, seen.yaw), shift(seen.x, seen.y);
    std::vector<float> ranges(beams, std::numeric_limits<float>::quiet_NaN());
    for (const Complex &point : deskewedPolarCode(*k->scan, k->twist)) {
      if (!std::isfinite(point.real()) || !std::isfinite(point.imag())) continue;
      const Complex p = turn * point + shift;
      const double range = std::abs(p);
      if (!map.isValidRange(range)) continue;
      const double index = std::round((std::arg(p) - map.angle_min) / increment);
      const auto bin = static_cast<std::size_t>(
          (static_cast<long long>(index) % static_cast<long long>(beams) + static_cast<long long>(beams)) %
          static_cast<long long>(beams));
      if (!(ranges[bin] <= range)) ranges[bin] = static_cast<float>(range);  // the nearest return of the keyframe
    }
    for (std::size_t n = 0; n < beams; ++n)
      if (std::isnan(map.ranges[n]) && !std::isnan(ranges[n])) map.ranges[n] = ranges[n];
  }
  return map;
}

}  // namespace contour_reg::odometry
