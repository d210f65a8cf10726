#include "contour_reg/core/contour_features.h"

#include <vector>

#include <gtest/gtest.h>

#include "scenes.h"

namespace contour_reg {
namespace {

void expectSameFeatures(const ContourFeatures &a, const ContourFeatures &b) {
  ASSERT_EQ(a.segments.size(), b.segments.size());
  for (std::size_t k = 0; k < a.segments.size(); ++k) {
    EXPECT_EQ(a.segments[k].points, b.segments[k].points);
    EXPECT_EQ(a.segments[k].beam_indices, b.segments[k].beam_indices);
  }
  ASSERT_EQ(a.contours.size(), b.contours.size());
  for (std::size_t k = 0; k < a.contours.size(); ++k) {
    EXPECT_EQ(a.contours[k].vertices, b.contours[k].vertices);
    EXPECT_EQ(a.contours[k].step, b.contours[k].step);
    EXPECT_EQ(a.contours[k].segment, b.contours[k].segment);
    EXPECT_EQ(a.responses[k].response, b.responses[k].response);
    EXPECT_EQ(a.responses[k].turn, b.responses[k].turn);
  }
  ASSERT_EQ(a.special_points.size(), b.special_points.size());
  for (std::size_t k = 0; k < a.special_points.size(); ++k) {
    const SpecialPoint &p = a.special_points[k], &q = b.special_points[k];
    EXPECT_EQ(p.position, q.position);
    EXPECT_EQ(p.corner_angle, q.corner_angle);
    EXPECT_EQ(p.orientation, q.orientation);
    EXPECT_EQ(p.contour, q.contour);
    EXPECT_EQ(p.vertex, q.vertex);
    EXPECT_EQ(p.fragment, q.fragment);
  }
}

// Features extracted into an object that held other scans' (more and fewer segments and
// corners, reused buffers) are exactly those extracted into a new one.
TEST(ContourFeatures, ReusedObjectGivesTheSameFeaturesAsANewOne) {
  const test::RoomWithBoxes room;
  const LaserScan busy = test::scanFrom(room.world, test::pose2d(0.0, 0.0, 0.0), 0.01, 1);
  const LaserScan other = test::scanFrom(room.world, test::pose2d(2.5, 1.5, 140.0), 0.01, 2);
  LaserScan sparse = busy;  // five beams lost in every forty: more, shorter segments
  for (std::size_t n = 0; n < sparse.ranges.size(); ++n)
    if (n % 40 < 5) sparse.ranges[n] = 0.0f;
  const ContourParams params;
  ContourFeatures reused;
  for (const LaserScan *scan : std::vector<const LaserScan *>{&busy, &sparse, &other, &busy, &other, &sparse}) {
    extractContourFeatures(*scan, params, reused);
    const ContourFeatures fresh = extractContourFeatures(*scan, params);
    ASSERT_FALSE(fresh.contours.empty());
    expectSameFeatures(reused, fresh);
  }
}

}  // namespace
}  // namespace contour_reg
