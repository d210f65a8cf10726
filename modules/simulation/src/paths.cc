#include "contour_reg/simulation/paths.h"

#include <algorithm>
#include <cmath>

namespace contour_reg::simulation {

namespace {

using V = Eigen::Vector2d;

V pointAt(const std::vector<V> &waypoints, double s) {
  for (std::size_t k = 0; k + 1 < waypoints.size(); ++k) {
    const double length = (waypoints[k + 1] - waypoints[k]).norm();
    if (s <= length || k + 2 == waypoints.size())
      return waypoints[k] + std::clamp(s / length, 0.0, 1.0) * (waypoints[k + 1] - waypoints[k]);
    s -= length;
  }
  return waypoints.back();
}

}  // namespace

std::vector<V> officePath(const std::string &shape) {
  if (shape == "L") return {V(2.0, 7.5), V(22.5, 7.5), V(22.5, 12.5)};
  if (shape == "S") return {V(2.0, 11.5), V(5.5, 11.5), V(5.5, 7.5), V(11.5, 7.5), V(11.5, 3.8), V(15.5, 3.8)};
  if (shape == "Y") return {V(3.5, 2.5), V(3.5, 7.5), V(13.0, 7.5), V(14.5, 8.3), V(14.5, 12.5)};
  if (shape == "O")
    return {V(11.5, 7.5), V(11.5, 4.2), V(15.3, 4.2), V(15.3, 1.2), V(11.5, 1.2), V(11.5, 4.2), V(11.5, 7.5)};
  if (shape == "line") return {V(1.5, 7.5), V(28.5, 7.5)};
  return {};
}

double pathLength(const std::vector<V> &waypoints) {
  double length = 0.0;
  for (std::size_t k = 0; k + 1 < waypoints.size(); ++k) length += (waypoints[k + 1] - waypoints[k]).norm();
  return length;
}

std::vector<Eigen::Isometry2d> samplePath(const std::vector<V> &waypoints, double spacing, double turn_radius) {
  std::vector<Eigen::Isometry2d> poses;
  if (waypoints.size() < 2 || !(spacing > 0.0)) return poses;
  const double length = pathLength(waypoints);
  const auto count = static_cast<std::size_t>(std::floor(length / spacing + 1e-9));
  for (std::size_t k = 0; k <= count + 1; ++k) {
    const double s = std::min(static_cast<double>(k) * spacing, length);
    if (k > count && (length - static_cast<double>(count) * spacing) < 1e-6) break;
    // The heading is that of the chord across +-turn_radius: smooth through the turns.
    const V ahead = pointAt(waypoints, std::min(s + turn_radius, length));
    const V behind = pointAt(waypoints, std::max(s - turn_radius, 0.0));
    Eigen::Isometry2d pose = Eigen::Isometry2d::Identity();
    pose.translate(pointAt(waypoints, s));
    pose.rotate(std::atan2(ahead.y() - behind.y(), ahead.x() - behind.x()));
    poses.push_back(pose);
  }
  return poses;
}

}  // namespace contour_reg::simulation
