#pragma once
/// @file office.h
/// Worlds made by code. The built-in office map: rooms off a corridor, doors, furniture, pillars and round
/// objects, about 30 m x 16 m. It is the bundled default world of the simulator. The built-in
/// door row: a corridor whose only features repeat every few metres.

#include <string>
#include <vector>

#include <Eigen/Core>

#include "contour_reg/simulation/world.h"

namespace contour_reg::simulation {

/// Builds the built-in office world. The free corridor runs along y in [6, 9] from x = 1 to 29;
/// rooms lie south (y < 6) and north (y > 9) of it.
World makeOfficeWorld();

/// A furnished 13 m x 9 m room: walls with a door recess and an alcove, boxes, a pillar,
/// a triangular cabinet and a round bin, so scans from anywhere in it see several corners.
/// The scene of the registration tests and benchmarks.
World makeFurnishedRoom();

/// The door row's period: a door recess every this many metres.
constexpr double kDoorRowPeriod = 3.0;

/// The built-in door row: a corridor 2.4 m wide (y in [0, 2.4]) and 60 m long (x in [0, 60]),
/// closed at both ends, with a door recess 0.9 m wide and 0.2 m deep every kDoorRowPeriod
/// metres along its south wall (the first at x = 1.5). Away from the ends, scans taken a whole
/// number of periods apart see the same: only the ends tell one door from the next.
World makeDoorRowWorld();

/// The door row's one path, "line": along the corridor's axis from x = 3 to 57 (empty for any other name).
std::vector<Eigen::Vector2d> doorRowPath(const std::string &name);

/// Whether `map` names a built-in world: "office" (makeOfficeWorld) or "doors" (makeDoorRowWorld).
bool isBuiltInWorld(const std::string &map);

/// The built-in world `map` names; an empty world for any other name.
World makeBuiltInWorld(const std::string &map);

/// The path `name` of the built-in world `map` (officePath, doorRowPath); empty when it has none.
std::vector<Eigen::Vector2d> builtInPath(const std::string &map, const std::string &name);

/// The built-in world `map` and its paths, for messages: "the office (S, L, Y, O, line)".
std::string builtInPathChoices(const std::string &map);

}  // namespace contour_reg::simulation
