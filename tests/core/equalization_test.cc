#include "contour_reg/core/equalization.h"

#include <cmath>
#include <string>

#include <gtest/gtest.h>

namespace contour_reg {
namespace {

// An L-shaped polyline with irregular spacing: 3 m along x, then 2 m along y.
ComplexSequence lShape() { return {{0, 0}, {0.3, 0}, {1.1, 0}, {1.15, 0}, {3, 0}, {3, 0.7}, {3, 0.75}, {3, 2}}; }

// Arc length of point q on the L shape (q must lie on it).
double arcOnLShape(const Complex &q) { return std::abs(q.imag()) < 1e-12 ? q.real() : 3.0 + q.imag(); }

TEST(Equalization, FixedCountGivesEqualPiecesAndKeepsTheLength) {  // eqs. (3)-(11)
  const ComplexSequence points = lShape();
  const EqualizedContour contour = equalizeByCount(points, 50);
  ASSERT_EQ(contour.elementCount(), 50u);
  EXPECT_NEAR(contour.step * 50, polylineLength(points), 1e-9);  // eq. (3)
  EXPECT_NEAR(contour.step, 0.1, 1e-12);
  for (std::size_t r = 0; r < contour.vertices.size(); ++r)
    EXPECT_NEAR(arcOnLShape(contour.vertices[r]), r * contour.step, 1e-9) << "vertex " << r;
  // The bend falls on a vertex, so every element is a straight chord of length e.
  for (std::size_t r = 0; r < 50; ++r) EXPECT_NEAR(std::abs(contour.element(r)), contour.step, 1e-9) << "element " << r;
  EXPECT_EQ(contour.vertices.front(), points.front());
  EXPECT_NEAR(std::abs(contour.vertices.back() - points.back()), 0.0, 1e-9);
}

TEST(Equalization, FixedCountOfNonDivisibleLength) {
  const ComplexSequence points = {{0, 0}, {0.37, 0}, {1.0, 0}};
  const EqualizedContour contour = equalizeByCount(points, 7);
  ASSERT_EQ(contour.elementCount(), 7u);
  double total = 0.0;
  for (std::size_t r = 0; r < 7; ++r) {
    EXPECT_NEAR(std::abs(contour.element(r)), 1.0 / 7.0, 1e-9);
    total += std::abs(contour.element(r));
  }
  EXPECT_NEAR(total, 1.0, 1e-9);
}

TEST(Equalization, FixedStepDropsTheRemainder) {
  const ComplexSequence points = lShape();
  const EqualizedContour contour = equalizeByStep(points, 0.3);
  EXPECT_EQ(contour.elementCount(), 16u);  // 5 m / 0.3 m = 16.7
  EXPECT_DOUBLE_EQ(contour.step, 0.3);
  EXPECT_NEAR(arcOnLShape(contour.vertices.back()), 4.8, 1e-9);
}

// Centred elements drop the remainder half at each end, so the points in reverse order give
// the same vertices in reverse order; the paper's start at the first point and drop it at
// the last.
TEST(Equalization, CentredElementsDoNotDependOnTheDirectionOfThePoints) {
  const ComplexSequence points = lShape();
  const ComplexSequence reversed(points.rbegin(), points.rend());
  EqualizedContour forward, backward;
  std::vector<double> arc;
  equalizeCentred(points, 0.3, forward, arc);
  equalizeCentred(reversed, 0.3, backward, arc);
  ASSERT_EQ(forward.elementCount(), 16u);  // 5 m / 0.3 m = 16.7: 0.2 m left over
  EXPECT_NEAR(arcOnLShape(forward.vertices.front()), 0.1, 1e-9);
  EXPECT_NEAR(arcOnLShape(forward.vertices.back()), 4.9, 1e-9);
  ASSERT_EQ(backward.vertices.size(), forward.vertices.size());
  for (std::size_t r = 0; r < forward.vertices.size(); ++r)
    EXPECT_NEAR(std::abs(forward.vertices[r] - backward.vertices[backward.vertices.size() - 1 - r]), 0.0, 1e-9)
        << "vertex " << r;
  const EqualizedContour paper = equalizeByStep(reversed, 0.3);
  EXPECT_NEAR(arcOnLShape(paper.vertices.back()), 0.2, 1e-9);  // the paper's: all 0.2 m at the end
}

// Each vertex knows how far apart the two raw points it lies between are: the covariance
// counts the samples on a sparse stretch by it (refinement.h).
TEST(Equalization, EachVertexKnowsTheSpacingOfItsRawPoints) {
  const ComplexSequence points = lShape();
  const EqualizedContour contour = equalizeByStep(points, 0.1);
  ASSERT_EQ(contour.spacing.size(), contour.vertices.size());
  const std::vector<double> arc = arcLengths(points);
  for (std::size_t r = 0; r < contour.vertices.size(); ++r) {
    // The length of a raw vector that holds the vertex (either one, for a vertex on a raw point).
    const double at = r * contour.step;
    bool held = false;
    for (std::size_t n = 0; n + 1 < points.size(); ++n)
      held |=
          arc[n] <= at + 1e-9 && at - 1e-9 <= arc[n + 1] && std::abs(contour.spacing[r] - (arc[n + 1] - arc[n])) < 1e-9;
    EXPECT_TRUE(held) << "vertex " << r << ": " << contour.spacing[r];
  }
  EXPECT_NEAR(contour.spacing[15], 1.85, 1e-9);  // 1.5 m lies between the raw points at 1.15 and 3 m
}

TEST(Equalization, SegmentsInFixedCountModeShareOneStep) {
  std::vector<ContourSegment> segments(2);
  segments[0].points = {{0, 0}, {3, 0}};
  segments[1].points = {{0, 1}, {1, 1}};
  EqualizationParams params;
  params.mode = EqualizationMode::kFixedCount;
  params.count = 40;
  const auto contours = equalizeSegments(segments, params);
  ASSERT_EQ(contours.size(), 2u);
  EXPECT_EQ(contours[0].elementCount(), 30u);
  EXPECT_EQ(contours[1].elementCount(), 10u);
  EXPECT_NEAR(contours[0].step, 0.1, 1e-12);
  EXPECT_EQ(contours[1].segment, 1);
}

// Elements finer than a millimetre (below any LIDAR's range noise) or more than 100 000 over a
// scan are settings errors: a micrometre step over a scan's 100 m of contour asks for 10^8
// elements and gigabytes.
TEST(Equalization, StepsFinerThanAMillimetreAreInvalid) {
  EqualizationParams params;
  std::string why;
  params.step = 1e-6;
  EXPECT_FALSE(params.validate(&why));
  EXPECT_NE(why.find("equalization.step"), std::string::npos) << why;
  params.step = 0.001;
  EXPECT_TRUE(params.validate());
  params.mode = EqualizationMode::kFixedCount;
  params.count = 1000000;
  EXPECT_FALSE(params.validate(&why));
  EXPECT_NE(why.find("equalization.count"), std::string::npos) << why;
  params.count = 100000;
  EXPECT_TRUE(params.validate());
}

TEST(Equalization, DegenerateInputGivesNoElements) {
  EXPECT_EQ(equalizeByStep({}, 0.1).elementCount(), 0u);
  EXPECT_EQ(equalizeByStep({{1, 1}}, 0.1).elementCount(), 0u);
  EXPECT_EQ(equalizeByStep({{0, 0}, {1, 0}}, 0.0).elementCount(), 0u);
  EXPECT_EQ(equalizeByCount({{0, 0}, {1, 0}}, 0).elementCount(), 0u);
}

}  // namespace
}  // namespace contour_reg
