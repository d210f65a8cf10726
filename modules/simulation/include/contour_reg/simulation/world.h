#pragma once
/// @file world.h
/// A 2-D world that a simulated LIDAR sees: line segments, circles and, optionally, an
/// occupancy grid (a floor-plan image).

#include <memory>
#include <vector>

#include <Eigen/Core>

#include "contour_reg/simulation/occupancy_grid.h"

namespace contour_reg::simulation {

struct Segment {
  Eigen::Vector2d a, b;
};

struct Circle {
  Eigen::Vector2d centre;
  double radius = 0.0;
};

/// Obstacles as segments, circles and an occupancy grid, in metres, world frame.
class World {
 public:
  void addSegment(const Eigen::Vector2d &a, const Eigen::Vector2d &b) { segments_.push_back({a, b}); }
  /// Adds the closed polygon through `corners` (the last joins the first).
  void addPolygon(const std::vector<Eigen::Vector2d> &corners);
  /// Adds an axis-aligned rectangle given two opposite corners.
  void addBox(const Eigen::Vector2d &min, const Eigen::Vector2d &max);
  void addCircle(const Eigen::Vector2d &centre, double radius) { circles_.push_back({centre, radius}); }

  /// Adds an occupancy grid; its occupied cells are obstacles and, for isOpen(), its
  /// unknown cells are out of bounds.
  void setGrid(std::shared_ptr<const OccupancyGrid> grid) { grid_ = std::move(grid); }

  const std::vector<Segment> &segments() const { return segments_; }
  const std::vector<Circle> &circles() const { return circles_; }
  const OccupancyGrid *grid() const { return grid_.get(); }

  /// Distance from `p` to the nearest obstacle, m (+inf in an empty world).
  double clearance(const Eigen::Vector2d &p) const;
  /// False where a robot cannot be: in an unknown or occupied grid cell, or outside the grid.
  bool isOpen(const Eigen::Vector2d &p) const { return !grid_ || grid_->isFree(p); }

  /// Distance along the ray from `origin` in unit direction `direction` to the first
  /// obstacle, or +inf when nothing is hit.
  double castRay(const Eigen::Vector2d &origin, const Eigen::Vector2d &direction) const;

 private:
  std::vector<Segment> segments_;
  std::vector<Circle> circles_;
  std::shared_ptr<const OccupancyGrid> grid_;
};

}  // namespace contour_reg::simulation
