// People walking about a simulated run: they keep clear of walls and of the LIDAR, they move,
// and a scan sees them in front of what it saw without them, never behind.
#include <cmath>

#include <gtest/gtest.h>

#include "contour_reg/simulation/lidar.h"
#include "contour_reg/simulation/office.h"
#include "contour_reg/simulation/paths.h"
#include "contour_reg/simulation/simulated_run.h"
#include "contour_reg/simulation/walkers.h"

namespace contour_reg::simulation {
namespace {

TEST(Walkers, WalkWithinTheOpenSpaceClearOfObstacles) {
  const World office = makeOfficeWorld();
  Walkers walkers(office, officePath("S"), 10, 3);
  ASSERT_EQ(walkers.people().size(), 10u);
  const std::vector<Walkers::Person> start = walkers.people();
  for (const Walkers::Person &person : start) {
    EXPECT_GE(person.radius, 0.2);
    EXPECT_LE(person.radius, 0.25);
    EXPECT_GE(person.velocity.norm(), 0.5);
    EXPECT_LE(person.velocity.norm(), 1.5);
  }
  double walked = 0.0;
  for (double t = 1.0; t <= 60.0; t += 1.0) {
    walkers.advanceTo(t);
    for (std::size_t k = 0; k < start.size(); ++k) {
      const Walkers::Person &person = walkers.people()[k];
      ASSERT_TRUE(office.isOpen(person.position)) << "person " << k << " at " << t << " s";
      ASSERT_GE(office.clearance(person.position), person.radius + kWalkerClearance - 1e-9)
          << "person " << k << " at " << t << " s";
    }
  }
  for (std::size_t k = 0; k < start.size(); ++k) walked += (walkers.people()[k].position - start[k].position).norm();
  EXPECT_GT(walked / static_cast<double>(start.size()), 1.0);  // they wander off, not stand still
}

TEST(Walkers, APersonAtTheLidarStepsAside) {
  const World office = makeOfficeWorld();
  const Walkers walkers(office, officePath("L"), 4, 5);
  ASSERT_EQ(walkers.people().size(), 4u);
  const std::size_t circles = office.circles().size();
  EXPECT_EQ(walkers.around(walkers.people().front().position + Eigen::Vector2d(0.3, 0.0)).circles().size(),
            circles + 3);
  EXPECT_EQ(walkers.around(Eigen::Vector2d(1e3, 1e3)).circles().size(), circles + 4);
}

// Without range noise and dropout, a run among people measures every beam at most as far as the
// same run without them, and the people cut some beams short.
TEST(SimulatedRun, PeopleOccludeAndNeverLengthenABeam) {
  const World office = makeOfficeWorld();
  RunSettings settings;
  settings.lidar = LidarModel::hokuyoUtm30lx();
  settings.lidar.range_noise = 0.0;
  settings.lidar.dropout = 0.0;
  settings.rate = 1.0;
  settings.speed = 1.0;
  const auto path = officePath("S");
  const SimulatedRun empty = simulateRun(office, path, settings);
  settings.people = 10;
  const SimulatedRun crowded = simulateRun(office, path, settings);
  ASSERT_EQ(crowded.log.entries.size(), empty.log.entries.size());
  int shorter = 0, scans_with_people = 0;
  for (std::size_t k = 0; k < empty.log.entries.size(); ++k) {
    const auto &a = empty.log.entries[k].scan.ranges, &b = crowded.log.entries[k].scan.ranges;
    ASSERT_EQ(a.size(), b.size());
    int here = 0;
    for (std::size_t n = 0; n < a.size(); ++n) {
      const bool both_finite = std::isfinite(a[n]) && std::isfinite(b[n]);
      if (both_finite) ASSERT_LE(b[n], a[n] + 1e-4) << "scan " << k << " beam " << n;
      if (!std::isfinite(b[n])) ASSERT_FALSE(std::isfinite(a[n])) << "scan " << k << " beam " << n;
      here += std::isfinite(b[n]) && (!std::isfinite(a[n]) || b[n] < a[n] - 0.3);
    }
    shorter += here;
    scans_with_people += here > 0;
  }
  EXPECT_GT(scans_with_people, static_cast<int>(empty.log.entries.size()) / 2);
  EXPECT_GT(shorter, 100);
}

}  // namespace
}  // namespace contour_reg::simulation
