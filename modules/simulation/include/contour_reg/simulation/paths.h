#pragma once
/// @file paths.h
/// Robot paths shaped like the paper's Fig. 3 experiment (S, L, Y, O): placed by hand in
/// the built-in office, or placed automatically in any other map; and poses along them.

#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "contour_reg/simulation/world.h"

namespace contour_reg::simulation {

/// The path shapes the experiment knows: S, L, Y, O.
const std::vector<std::string> &pathShapes();

/// Waypoints of a named path in the built-in office: "S" (an S-bend), "L" (one turn),
/// "Y" (a stem and a branch), "O" (a closed loop), "line" (the corridor). Empty if unknown.
std::vector<Eigen::Vector2d> officePath(const std::string &shape);

/// The shape of a named path in its own frame: the office path moved to start at the origin.
std::vector<Eigen::Vector2d> pathShape(const std::string &shape);

/// Length of the polyline through `waypoints`.
double pathLength(const std::vector<Eigen::Vector2d> &waypoints);

/// The pose at arc length `s` along the polyline: the point at `s`, heading along the chord
/// from s - turn_radius to s + turn_radius, so the robot turns smoothly through corners.
Eigen::Isometry2d poseAlongPath(const std::vector<Eigen::Vector2d> &waypoints, double s, double turn_radius = 0.4);

/// Poses every `spacing` metres along the polyline (and one at its end), as poseAlongPath.
std::vector<Eigen::Isometry2d> samplePath(const std::vector<Eigen::Vector2d> &waypoints, double spacing,
                                          double turn_radius = 0.4);

struct PlacementOptions {
  double clearance = 0.6;    ///< m, least distance from every point of the path to an obstacle
  double sample_step = 0.2;  ///< m, spacing of the checked points along the path
  /// m, spacing of the tried start positions; wider in maps over 100 m across, which are tried
  /// at 200 positions along each axis
  double search_step = 0.5;
  std::vector<double> scales = {1.0, 0.8, 0.6, 0.45};  ///< shape sizes tried, largest first
  double sight_range = 30.0;                           ///< m: from every waypoint, walls must be seen within it ...
  double enclosed_fraction = 0.9;                      ///< ... in at least this fraction of directions
};

/// Places `shape` in `world`: turned by a multiple of 90 deg, mirrored or not, scaled and
/// moved so that every point of the path is open and keeps the clearance, and walls are in
/// sight all round (inside the building, not outside it). The largest scale that fits wins,
/// then the largest clearance (counted up to 1 m), then the position nearest the middle of
/// the map. Empty when the shape fits nowhere.
std::vector<Eigen::Vector2d> placePath(const World &world, const std::vector<Eigen::Vector2d> &shape,
                                       const PlacementOptions &options = {});

}  // namespace contour_reg::simulation
