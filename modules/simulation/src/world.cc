#include "contour_reg/simulation/world.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "contour_reg/core/types.h"

namespace contour_reg::simulation {

namespace {

double cross(const Eigen::Vector2d &a, const Eigen::Vector2d &b) { return a.x() * b.y() - a.y() * b.x(); }

// Ray-segment intersection distance, or +inf.
double hitSegment(const Segment &s, const Eigen::Vector2d &origin, const Eigen::Vector2d &direction) {
  const Eigen::Vector2d edge = s.b - s.a;
  const double denominator = cross(direction, edge);
  if (std::abs(denominator) < 1e-12) return std::numeric_limits<double>::infinity();
  const Eigen::Vector2d to_a = s.a - origin;
  const double t = cross(to_a, edge) / denominator;       // along the ray
  const double u = cross(to_a, direction) / denominator;  // along the segment
  if (t <= 0.0 || u < 0.0 || u > 1.0) return std::numeric_limits<double>::infinity();
  return t;
}

double hitCircle(const Circle &c, const Eigen::Vector2d &origin, const Eigen::Vector2d &direction) {
  const Eigen::Vector2d to_centre = c.centre - origin;
  const double along = to_centre.dot(direction);
  const double miss2 = to_centre.squaredNorm() - along * along;
  const double r2 = c.radius * c.radius;
  if (miss2 > r2) return std::numeric_limits<double>::infinity();
  const double half_chord = std::sqrt(r2 - miss2);
  const double t = along - half_chord;
  if (t > 0.0) return t;
  return std::numeric_limits<double>::infinity();  // origin inside or circle behind
}

}  // namespace

void World::addPolygon(const std::vector<Eigen::Vector2d> &corners) {
  for (std::size_t k = 0; k < corners.size(); ++k) addSegment(corners[k], corners[(k + 1) % corners.size()]);
}

void World::addBox(const Eigen::Vector2d &min, const Eigen::Vector2d &max) {
  addPolygon({min, {max.x(), min.y()}, max, {min.x(), max.y()}});
}

double World::castRay(const Eigen::Vector2d &origin, const Eigen::Vector2d &direction) const {
  double best = std::numeric_limits<double>::infinity();
  for (const Segment &s : segments_) best = std::min(best, hitSegment(s, origin, direction));
  for (const Circle &c : circles_) best = std::min(best, hitCircle(c, origin, direction));
  if (grid_) best = std::min(best, grid_->castRay(origin, direction));
  return best;
}

double World::clearance(const Eigen::Vector2d &p) const {
  double best = std::numeric_limits<double>::infinity();
  for (const Segment &s : segments_) best = std::min(best, distanceToSegment(p, s.a, s.b));
  for (const Circle &c : circles_) best = std::min(best, std::max(0.0, (p - c.centre).norm() - c.radius));
  if (grid_) best = std::min(best, grid_->clearance(p));
  return best;
}

}  // namespace contour_reg::simulation
