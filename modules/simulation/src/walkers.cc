#include "contour_reg/simulation/walkers.h"

#include <cmath>

#include "contour_reg/simulation/paths.h"

namespace contour_reg::simulation {

namespace {

constexpr double kStep = 0.1;          // s between the walkers' moves
constexpr int kPlacementTries = 1000;  // per person
constexpr int kTurnTries = 20;

}  // namespace

Walkers::Walkers(const World &world, const std::vector<Eigen::Vector2d> &waypoints, int count, unsigned seed)
    : world_(&world), rng_(seed) {
  const double length = pathLength(waypoints);
  if (count <= 0 || waypoints.size() < 2 || !(length > 0.0)) return;
  std::uniform_real_distribution<double> along(0.0, length), unit(0.0, 1.0), size(0.2, 0.25);
  for (int n = 0; n < count; ++n) {
    for (int attempt = 0; attempt < kPlacementTries; ++attempt) {
      const Eigen::Vector2d near = poseAlongPath(waypoints, along(rng_)).translation();
      const double reach = kWalkerReach * std::sqrt(unit(rng_)), bearing = 2.0 * M_PI * unit(rng_);
      Person person;
      person.position = near + reach * Eigen::Vector2d(std::cos(bearing), std::sin(bearing));
      person.radius = size(rng_);
      if (!roomFor(person.position, person.radius)) continue;
      turn(person);
      people_.push_back(person);
      break;
    }
  }
}

bool Walkers::roomFor(const Eigen::Vector2d &p, double radius) const {
  return world_->isOpen(p) && world_->clearance(p) >= radius + kWalkerClearance;
}

void Walkers::turn(Person &person) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int attempt = 0; attempt < kTurnTries; ++attempt) {
    const double heading = 2.0 * M_PI * unit(rng_), speed = 0.5 + unit(rng_);
    person.velocity = speed * Eigen::Vector2d(std::cos(heading), std::sin(heading));
    if (roomFor(person.position + kStep * person.velocity, person.radius)) return;
  }
  person.velocity.setZero();  // boxed in: stands still
}

void Walkers::advanceTo(double t) {
  while (time_ + kStep <= t + 1e-9) {
    for (Person &person : people_) {
      const Eigen::Vector2d next = person.position + kStep * person.velocity;
      if (roomFor(next, person.radius))
        person.position = next;
      else
        turn(person);
    }
    time_ += kStep;
  }
}

World Walkers::around(const Eigen::Vector2d &sensor) const {
  World seen = *world_;
  for (const Person &person : people_)
    if ((person.position - sensor).norm() >= person.radius + kWalkerClearance)
      seen.addCircle(person.position, person.radius);
  return seen;
}

}  // namespace contour_reg::simulation
