#pragma once
/// @file world.h
/// A 2-D world of line segments and circles that a simulated LIDAR sees.

#include <vector>

#include <Eigen/Core>

namespace contour_reg::simulation {

struct Segment {
  Eigen::Vector2d a, b;
};

struct Circle {
  Eigen::Vector2d centre;
  double radius = 0.0;
};

/// Obstacles as segments and circles, in metres, world frame.
class World {
 public:
  void addSegment(const Eigen::Vector2d &a, const Eigen::Vector2d &b) { segments_.push_back({a, b}); }
  /// Adds the closed polygon through `corners` (the last joins the first).
  void addPolygon(const std::vector<Eigen::Vector2d> &corners);
  /// Adds an axis-aligned rectangle given two opposite corners.
  void addBox(const Eigen::Vector2d &min, const Eigen::Vector2d &max);
  void addCircle(const Eigen::Vector2d &centre, double radius) { circles_.push_back({centre, radius}); }

  const std::vector<Segment> &segments() const { return segments_; }
  const std::vector<Circle> &circles() const { return circles_; }

  /// Distance along the ray from `origin` in unit direction `direction` to the first
  /// obstacle, or +inf when nothing is hit.
  double castRay(const Eigen::Vector2d &origin, const Eigen::Vector2d &direction) const;

 private:
  std::vector<Segment> segments_;
  std::vector<Circle> circles_;
};

}  // namespace contour_reg::simulation
