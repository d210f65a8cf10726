#pragma once
/// @file walkers.h
/// People walking through a simulated world while the robot drives: what a LIDAR sees in a
/// hospital corridor or an office at lunchtime besides the walls.
///
/// At a LIDAR's height a person is a circle of 0.2-0.25 m radius (legs and body seen as one).
/// Each starts at a random open spot within kWalkerReach of a random point of the robot's path,
/// kWalkerClearance from any obstacle, and walks straight at 0.5-1.5 m/s in a random direction;
/// where the next step would leave the open space or come that close to an obstacle, it turns to
/// another random direction. People pass through one another, and a person in the robot's way
/// steps aside: one whose circle comes within kWalkerClearance of the LIDAR is left out of that
/// scan. They move between scans, not during one.

#include <random>
#include <vector>

#include <Eigen/Core>

#include "contour_reg/simulation/world.h"

namespace contour_reg::simulation {

/// m: people start this far from the robot's path at most.
constexpr double kWalkerReach = 4.0;
/// m: the gap people keep from walls, furniture and the LIDAR.
constexpr double kWalkerClearance = 0.3;

class Walkers {
 public:
  /// `count` people about the path through `waypoints` in `world`, placed with `seed`; fewer
  /// when the open space near the path is too small for them. `world` must outlive them.
  Walkers(const World &world, const std::vector<Eigen::Vector2d> &waypoints, int count, unsigned seed);

  /// Walks everyone on to time `t` (s from the start; earlier times leave them where they are).
  void advanceTo(double t);

  /// `world` with the people in it as circles, leaving out those within kWalkerClearance of `sensor`.
  World around(const Eigen::Vector2d &sensor) const;

  struct Person {
    Eigen::Vector2d position;
    Eigen::Vector2d velocity;  ///< m/s
    double radius = 0.2;       ///< m
  };
  const std::vector<Person> &people() const { return people_; }

 private:
  bool roomFor(const Eigen::Vector2d &p, double radius) const;  // open and clear of obstacles
  void turn(Person &person);

  const World *world_;
  std::vector<Person> people_;
  std::mt19937 rng_;
  double time_ = 0.0;
};

}  // namespace contour_reg::simulation
