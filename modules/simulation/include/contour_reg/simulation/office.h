#pragma once
/// @file office.h
/// Worlds made by code. The built-in office map: rooms off a corridor, doors, furniture, pillars and round
/// objects, about 30 m x 16 m. It is the bundled default world of the simulator.

#include "contour_reg/simulation/world.h"

namespace contour_reg::simulation {

/// Builds the built-in office world. The free corridor runs along y in [6, 9] from x = 1 to 29;
/// rooms lie south (y < 6) and north (y > 9) of it.
World makeOfficeWorld();

/// A furnished 13 m x 9 m room: walls with a door recess and an alcove, boxes, a pillar,
/// a triangular cabinet and a round bin, so scans from anywhere in it see several corners.
/// The scene of the registration tests and benchmarks.
World makeFurnishedRoom();

}  // namespace contour_reg::simulation
