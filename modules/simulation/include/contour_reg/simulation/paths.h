#pragma once
/// @file paths.h
/// Robot paths through the built-in office, shaped like the paper's Fig. 3 experiment
/// (S, L, Y, O), and their sampling into scan poses.

#include <string>
#include <vector>

#include <Eigen/Geometry>

namespace contour_reg::simulation {

/// Waypoints of a named path in the built-in office: "S" (an S-bend), "L" (one turn),
/// "Y" (a stem and a branch), "O" (a closed loop), "line" (the corridor). Empty if unknown.
std::vector<Eigen::Vector2d> officePath(const std::string &shape);

/// Length of the polyline through `waypoints`.
double pathLength(const std::vector<Eigen::Vector2d> &waypoints);

/// Poses every `spacing` metres along the polyline (and one at its end). The heading
/// follows the path, smoothed over `turn_radius` metres around each waypoint.
std::vector<Eigen::Isometry2d> samplePath(const std::vector<Eigen::Vector2d> &waypoints, double spacing,
                                          double turn_radius = 0.4);

}  // namespace contour_reg::simulation
