#include "contour_reg/simulation/paths.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace contour_reg::simulation {

namespace {

using V = Eigen::Vector2d;

// placePath tries start positions search_step apart, but no more than this many along each
// axis of the map: a map of hundreds of metres is searched more coarsely, not for hours.
constexpr double kMostPositions = 200.0;

V pointAt(const std::vector<V> &waypoints, double s) {
  for (std::size_t k = 0; k + 1 < waypoints.size(); ++k) {
    const double length = (waypoints[k + 1] - waypoints[k]).norm();
    if (s <= length || k + 2 == waypoints.size())
      return waypoints[k] + std::clamp(length > 0.0 ? s / length : 0.0, 0.0, 1.0) * (waypoints[k + 1] - waypoints[k]);
    s -= length;
  }
  return waypoints.back();
}

// Points every `step` m along the polyline, its end included.
std::vector<V> pointsAlong(const std::vector<V> &waypoints, double step) {
  std::vector<V> points;
  const double length = pathLength(waypoints);
  for (double s = 0.0; s < length; s += step) points.push_back(pointAt(waypoints, s));
  points.push_back(waypoints.back());
  return points;
}

// Box the map covers: the grid, else the obstacles.
Eigen::AlignedBox2d mapBounds(const World &world) {
  Eigen::AlignedBox2d box;
  if (const OccupancyGrid *grid = world.grid()) {
    box.extend(grid->origin());
    box.extend(grid->origin() + grid->resolution() * V(grid->width(), grid->height()));
  }
  for (const Segment &s : world.segments()) box.extend(s.a).extend(s.b);
  for (const Circle &c : world.circles()) box.extend(c.centre);
  return box;
}

bool enclosed(const World &world, const V &point, const PlacementOptions &options) {
  constexpr int kDirections = 36;
  int seen = 0;
  for (int k = 0; k < kDirections; ++k) {
    const double angle = 2.0 * M_PI * k / kDirections;
    if (world.castRay(point, {std::cos(angle), std::sin(angle)}) <= options.sight_range) ++seen;
  }
  return seen >= options.enclosed_fraction * kDirections;
}

}  // namespace

const std::vector<std::string> &pathShapes() {
  static const std::vector<std::string> shapes = {"S", "L", "Y", "O"};
  return shapes;
}

std::vector<V> officePath(const std::string &shape) {
  if (shape == "L") return {V(2.0, 7.5), V(22.5, 7.5), V(22.5, 11.4)};
  if (shape == "S") return {V(2.0, 11.5), V(5.5, 11.5), V(5.5, 7.5), V(11.5, 7.5), V(11.5, 3.8), V(15.5, 3.8)};
  if (shape == "Y") return {V(3.5, 2.5), V(3.5, 7.5), V(13.0, 7.5), V(14.5, 8.3), V(14.5, 12.5)};
  if (shape == "O")
    return {V(11.5, 7.5), V(11.5, 4.2), V(15.3, 4.2), V(15.3, 1.2), V(11.5, 1.2), V(11.5, 4.2), V(11.5, 7.5)};
  if (shape == "line") return {V(1.5, 7.5), V(28.5, 7.5)};
  return {};
}

std::vector<V> pathShape(const std::string &shape) {
  std::vector<V> waypoints = officePath(shape);
  if (waypoints.empty()) return waypoints;
  const V start = waypoints.front();
  for (V &w : waypoints) w -= start;
  return waypoints;
}

double pathLength(const std::vector<V> &waypoints) {
  double length = 0.0;
  for (std::size_t k = 0; k + 1 < waypoints.size(); ++k) length += (waypoints[k + 1] - waypoints[k]).norm();
  return length;
}

Eigen::Isometry2d poseAlongPath(const std::vector<V> &waypoints, double s, double turn_radius) {
  Eigen::Isometry2d pose = Eigen::Isometry2d::Identity();
  if (waypoints.empty()) return pose;
  const double length = pathLength(waypoints);
  s = std::clamp(s, 0.0, length);
  const V ahead = pointAt(waypoints, std::min(s + turn_radius, length));
  const V behind = pointAt(waypoints, std::max(s - turn_radius, 0.0));
  pose.translate(pointAt(waypoints, s));
  pose.rotate(std::atan2(ahead.y() - behind.y(), ahead.x() - behind.x()));
  return pose;
}

std::vector<Eigen::Isometry2d> samplePath(const std::vector<V> &waypoints, double spacing, double turn_radius) {
  std::vector<Eigen::Isometry2d> poses;
  if (waypoints.size() < 2 || !(spacing > 0.0)) return poses;
  const double length = pathLength(waypoints);
  const auto count = static_cast<std::size_t>(std::floor(length / spacing + 1e-9));
  for (std::size_t k = 0; k <= count; ++k)
    poses.push_back(poseAlongPath(waypoints, static_cast<double>(k) * spacing, turn_radius));
  if (length - static_cast<double>(count) * spacing > 1e-6)
    poses.push_back(poseAlongPath(waypoints, length, turn_radius));
  return poses;
}

std::vector<V> placePath(const World &world, const std::vector<V> &shape, const PlacementOptions &options) {
  if (shape.size() < 2) return {};
  const Eigen::AlignedBox2d bounds = mapBounds(world);
  if (bounds.isEmpty()) return {};
  const V middle = bounds.center();
  // Every search_step across the map, but at most kMostPositions along each axis.
  const double step = std::max(options.search_step, bounds.sizes().maxCoeff() / kMostPositions);
  if (!(step > 0.0) || !std::isfinite(step)) return {};
  const Eigen::Matrix<long, 2, 1> positions = (bounds.sizes() / step).array().floor().cast<long>() + 1;
  for (double scale : options.scales) {
    struct Candidate {
      std::vector<V> waypoints;
      double score, distance;
    };
    std::vector<Candidate> candidates;
    for (int turn = 0; turn < 4; ++turn) {
      for (int mirror = 0; mirror < 2; ++mirror) {
        Eigen::Matrix2d linear = Eigen::Rotation2Dd(turn * M_PI / 2.0).toRotationMatrix() * scale;
        if (mirror) linear = linear * Eigen::Vector2d(1.0, -1.0).asDiagonal();
        std::vector<V> local;
        for (const V &w : shape) local.push_back(linear * w);
        const std::vector<V> checks = pointsAlong(local, options.sample_step);
        for (long i = 0; i < positions.x(); ++i) {
          for (long j = 0; j < positions.y(); ++j) {
            const V offset = bounds.min() + step * V(static_cast<double>(i), static_cast<double>(j));
            double least = std::numeric_limits<double>::infinity();
            for (const V &c : checks) {
              const V p = c + offset;
              if (!world.isOpen(p)) {
                least = 0.0;
                break;
              }
              least = std::min(least, world.clearance(p));
              if (least < options.clearance) break;
            }
            if (least < options.clearance) continue;
            std::vector<V> placed;
            V centroid = V::Zero();
            for (const V &w : local) {
              placed.push_back(w + offset);
              centroid += placed.back() / static_cast<double>(local.size());
            }
            candidates.push_back({std::move(placed), std::min(least, 1.0), (centroid - middle).norm()});
          }
        }
      }
    }
    std::sort(candidates.begin(), candidates.end(), [](const Candidate &a, const Candidate &b) {
      return a.score != b.score ? a.score > b.score : a.distance < b.distance;
    });
    for (const Candidate &candidate : candidates) {
      const bool all_enclosed = std::all_of(candidate.waypoints.begin(), candidate.waypoints.end(),
                                            [&](const V &w) { return enclosed(world, w, options); });
      if (all_enclosed) return candidate.waypoints;
    }
  }
  return {};
}

}  // namespace contour_reg::simulation
