#include "contour_reg/core/contour.h"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

namespace contour_reg {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

LaserScan straightWallScan(std::size_t beams, double distance) {
  LaserScan scan;
  scan.angle_min = -M_PI / 4;
  scan.angle_increment = (M_PI / 2) / static_cast<double>(beams - 1);
  scan.range_max = 30.0;
  for (std::size_t n = 0; n < beams; ++n)
    scan.ranges.push_back(static_cast<float>(distance / std::cos(scan.bearing(n))));
  return scan;
}

TEST(PolarCode, PutsBeamEndPointsInThePlane) {  // eq. (1)
  LaserScan scan;
  scan.angle_min = 0.0;
  scan.angle_increment = M_PI / 2;
  scan.range_max = 10.0;
  scan.ranges = {1.0f, 2.0f, 3.0f};
  const ComplexSequence code = polarCode(scan);
  ASSERT_EQ(code.size(), 3u);
  EXPECT_NEAR(code[0].real(), 1.0, 1e-12);
  EXPECT_NEAR(code[0].imag(), 0.0, 1e-12);
  EXPECT_NEAR(code[1].real(), 0.0, 1e-12);
  EXPECT_NEAR(code[1].imag(), 2.0, 1e-12);
  EXPECT_NEAR(code[2].real(), -3.0, 1e-12);
}

TEST(PolarCode, MarksInvalidBeamsAsNaN) {
  LaserScan scan;
  scan.angle_increment = 0.01;
  scan.range_min = 0.1;
  scan.range_max = 10.0;
  scan.ranges = {1.0f,
                 std::numeric_limits<float>::quiet_NaN(),
                 std::numeric_limits<float>::infinity(),
                 0.0f,
                 -1.0f,
                 0.05f,
                 10.0f,
                 12.0f,
                 9.99f};
  const ComplexSequence code = polarCode(scan);
  ASSERT_EQ(code.size(), scan.ranges.size());
  EXPECT_TRUE(isFinite(code[0]));
  for (std::size_t n = 1; n <= 7; ++n) EXPECT_FALSE(isFinite(code[n])) << "beam " << n;
  EXPECT_TRUE(isFinite(code[8]));
}

TEST(DifferentialCode, IsTheSequenceOfDifferences) {  // eq. (2)
  const ComplexSequence points = {{0, 0}, {1, 0}, {1, 2}};
  const ComplexSequence code = differentialCode(points);
  ASSERT_EQ(code.size(), 2u);
  EXPECT_EQ(code[0], Complex(1, 0));
  EXPECT_EQ(code[1], Complex(0, 2));
  EXPECT_DOUBLE_EQ(polylineLength(points), 3.0);
  EXPECT_TRUE(differentialCode({}).empty());
}

TEST(Segmentation, OneWallIsOneSegment) {
  const LaserScan scan = straightWallScan(200, 3.0);
  const auto segments = splitIntoSegments(polarCode(scan), SegmentationParams{});
  ASSERT_EQ(segments.size(), 1u);
  EXPECT_EQ(segments[0].points.size(), 200u);
  EXPECT_EQ(segments[0].beam_indices.front(), 0);
  EXPECT_EQ(segments[0].beam_indices.back(), 199);
}

TEST(Segmentation, InvalidBeamsSplitSegments) {
  LaserScan scan = straightWallScan(200, 3.0);
  scan.ranges[100] = std::numeric_limits<float>::quiet_NaN();
  const auto segments = splitIntoSegments(polarCode(scan), SegmentationParams{});
  ASSERT_EQ(segments.size(), 2u);
  EXPECT_EQ(segments[0].beam_indices.back(), 99);
  EXPECT_EQ(segments[1].beam_indices.front(), 101);
}

TEST(Segmentation, RangeJumpsSplitSegments) {
  LaserScan scan = straightWallScan(200, 3.0);
  for (std::size_t n = 120; n < 200; ++n) scan.ranges[n] += 2.0f;  // an occluding edge at beam 120
  const auto segments = splitIntoSegments(polarCode(scan), SegmentationParams{});
  ASSERT_EQ(segments.size(), 2u);
  EXPECT_EQ(segments[0].beam_indices.back(), 119);
  EXPECT_EQ(segments[1].beam_indices.front(), 120);

  SegmentationParams tolerant;
  tolerant.max_gap = 5.0;  // a threshold above the jump keeps the scan whole
  EXPECT_EQ(splitIntoSegments(polarCode(scan), tolerant).size(), 1u);
}

TEST(Segmentation, DropsShortSegmentsAndHandlesEmptyInput) {
  ComplexSequence code = {{1, 0}, {1, 0.01}, {kNaN, kNaN}, {1, 0.5}, {1, 0.51}, {1, 0.52}};
  EXPECT_TRUE(splitIntoSegments(code, SegmentationParams{}).empty());
  EXPECT_TRUE(splitIntoSegments({}, SegmentationParams{}).empty());
  const ComplexSequence all_invalid(50, Complex(kNaN, kNaN));
  EXPECT_TRUE(splitIntoSegments(all_invalid, SegmentationParams{}).empty());
}

TEST(Segmentation, ValidateNamesTheBadValue) {
  SegmentationParams params;
  params.max_gap = -1.0;
  std::string why;
  EXPECT_FALSE(params.validate(&why));
  EXPECT_NE(why.find("max_gap"), std::string::npos);
  EXPECT_TRUE(SegmentationParams{}.validate());
}

}  // namespace
}  // namespace contour_reg
