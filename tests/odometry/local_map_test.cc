#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "contour_reg/odometry/local_map.h"

namespace contour_reg::odometry {
namespace {

LaserScan threeBeams(double angle_min, float range) {
  LaserScan scan;
  scan.angle_min = angle_min;
  scan.angle_increment = 0.01;
  scan.range_max = 30.0;
  scan.ranges = {range, range, range};
  return scan;
}

// The bin of the map nearest to `bearing`.
float rangeAt(const LaserScan &map, double bearing) {
  const double index = std::round((bearing - map.angle_min) / map.angle_increment);
  const auto beams = static_cast<long long>(map.ranges.size());
  return map.ranges[static_cast<std::size_t>((static_cast<long long>(index) % beams + beams) % beams)];
}

// The newest keyframe looks back the way the older one came: it keeps its own beams, and the
// older keyframe's returns fill the bearings it did not see, at their range from the newest.
TEST(LocalMap, TheNewestKeyframeKeepsItsBeamsAndOlderOnesFillWhatItDidNotSee) {
  const LaserScan older_left = threeBeams(M_PI / 2 - 0.01, 1.0f);  // 1 m to the left of the older keyframe
  const LaserScan older_back = threeBeams(M_PI - 0.01, 1.0f);      // 1 m behind it
  const LaserScan newest = threeBeams(-0.01, 3.0f);                // 3 m ahead of the newest
  // The newest stands 0.5 m ahead of the older keyframes, turned round.
  const io::Pose2D older_pose{0.0, 0.0, 0.0}, newest_pose{0.5, 0.0, M_PI};
  const LaserScan map =
      renderLocalMap({{&older_left, {}, older_pose}, {&older_back, {}, older_pose}, {&newest, {}, newest_pose}});
  EXPECT_NEAR(map.angle_increment, 0.01, 1e-12);
  EXPECT_EQ(map.ranges.size(), static_cast<std::size_t>(std::ceil(2 * M_PI / 0.01)));
  EXPECT_FLOAT_EQ(rangeAt(map, 0.0), 3.0f);  // the newest's own, over the older point 1.5 m away there
  // 1 m left of the older keyframe is 0.5 m back and 1 m to the right of the newest.
  EXPECT_NEAR(rangeAt(map, std::atan2(-1.0, 0.5)), std::hypot(0.5, 1.0), 0.02);
  EXPECT_TRUE(std::isnan(rangeAt(map, M_PI / 2)));
  const std::size_t seen = std::count_if(map.ranges.begin(), map.ranges.end(), [](float r) { return !std::isnan(r); });
  EXPECT_GE(seen, 5u);
  EXPECT_LE(seen, 6u);
  EXPECT_TRUE(renderLocalMap({}).ranges.empty());
}

}  // namespace
}  // namespace contour_reg::odometry
