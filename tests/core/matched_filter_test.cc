#include "contour_reg/core/matched_filter.h"

#include <cmath>

#include <gtest/gtest.h>

namespace contour_reg {
namespace {

constexpr double kDeg = M_PI / 180.0;

// An equalized contour along a corner of angle `angle` turning by `turn`, arms of `arm` m.
EqualizedContour corner(double angle, int turn, double arm = 1.0, double step = 0.05, double heading = 0.3) {
  const Complex first = std::polar(1.0, heading);
  const Complex second = first * std::polar(1.0, turn * (M_PI - angle));
  const ComplexSequence raw = {Complex(2, 1) - arm * first, Complex(2, 1), Complex(2, 1) + arm * second};
  return equalizeByStep(raw, step);
}

TEST(MatchedFilter, ReferenceCornerMatchesItselfAtAnyRotationAndScale) {  // eq. (12)
  const ComplexSequence reference = referenceCorner(5, 90 * kDeg, 1);
  ComplexSequence window = reference;
  for (auto &v : window) v *= std::polar(0.37, 1.2);
  EXPECT_NEAR(matchedFilterOutput(window, reference), 1.0, 1e-12);
  const ComplexSequence line(10, Complex(1, 0));
  EXPECT_NEAR(matchedFilterOutput(line, reference), std::cos(45 * kDeg), 1e-12);
  EXPECT_EQ(matchedFilterOutput(ComplexSequence(10, 0.0), reference), 0.0);
}

TEST(MatchedFilter, PeaksAtTheVertexOfAnExactCorner) {  // eq. (13)
  CornerFilterParams params;
  const EqualizedContour contour = corner(90 * kDeg, 1);
  const CornerResponse response = filterCorners(contour, params);
  ASSERT_EQ(response.response.size(), contour.vertices.size());
  std::size_t peak = 0;
  for (std::size_t n = 0; n < response.response.size(); ++n)
    if (response.response[n] > response.response[peak]) peak = n;
  EXPECT_EQ(peak, 20u);  // 1 m arm / 0.05 m step
  // A perfect 90-degree corner: eta_corner = 1, eta_line = cos(45 deg).
  EXPECT_NEAR(response.response[peak], 1.0 - std::cos(45 * kDeg), 1e-9);
  EXPECT_NEAR(response.corner_angle[peak], 90 * kDeg, 1e-12);
  EXPECT_EQ(response.turn[peak], 1);
}

TEST(MatchedFilter, DistinguishesTurnDirectionsAndPicksTheBankAngle) {
  CornerFilterParams params;
  for (double angle : {60.0, 120.0}) {
    for (int turn : {1, -1}) {
      const CornerResponse response = filterCorners(corner(angle * kDeg, turn), params);
      EXPECT_EQ(response.turn[20], turn) << angle;
      EXPECT_NEAR(response.corner_angle[20], angle * kDeg, 1e-12);
    }
  }
}

TEST(MatchedFilter, PrefixSumFormEqualsTheDirectFormula) {
  CornerFilterParams params;
  params.corner_angles_deg = {75.0};
  const EqualizedContour contour = corner(80 * kDeg, -1, 0.8, 0.07);
  const CornerResponse response = filterCorners(contour, params);
  const int s = params.arm_elements;
  for (std::size_t n = s; n + s < contour.vertices.size(); ++n) {
    ComplexSequence window;
    for (std::size_t r = n - s; r < n + s; ++r) window.push_back(contour.element(r));
    double best = 0.0;
    for (int turn : {1, -1}) {
      const double c = matchedFilterOutput(window, referenceCorner(s, 75 * kDeg, turn)) -
                       matchedFilterOutput(window, ComplexSequence(2 * s, Complex(1, 0)));
      best = std::max(best, c);
    }
    EXPECT_NEAR(response.response[n], best, 1e-12) << "vertex " << n;
  }
}

// Every window of a winding contour, with the default bank: the windows whose arms turn by
// less than half the bank's smallest turn are answered before the bank is searched, the others
// after; both must give what the direct formula gives over every bank element.
TEST(MatchedFilter, EveryWindowOfAWindingContourEqualsTheDirectFormula) {
  CornerFilterParams params;
  ComplexSequence raw = {Complex(0, 0)};
  double heading = 0.0;
  for (int k = 0; k < 40; ++k) {  // legs of 0.3-0.7 m, turns of -70 to 70 deg and a few straight
    heading += (k % 5 == 0 ? 0.0 : ((k * 37) % 141 - 70) * kDeg);
    raw.push_back(raw.back() + std::polar(0.3 + 0.01 * ((k * 13) % 41), heading));
  }
  const EqualizedContour contour = equalizeByStep(raw, 0.05);
  const CornerResponse response = filterCorners(contour, params);
  const int s = params.arm_elements;
  const ComplexSequence line(2 * s, Complex(1, 0));
  int straight = 0, corners = 0;
  for (std::size_t n = s; n + s < contour.vertices.size(); ++n) {
    ComplexSequence window;
    for (std::size_t r = n - s; r < n + s; ++r) window.push_back(contour.element(r));
    double best = 0.0, best_angle = M_PI;
    int best_turn = 0;
    for (double degrees : params.corner_angles_deg)
      for (int turn : {1, -1}) {
        const double c =
            matchedFilterOutput(window, referenceCorner(s, degrees * kDeg, turn)) - matchedFilterOutput(window, line);
        if (c > best) {
          best = c;
          best_angle = degrees * kDeg;
          best_turn = turn;
        }
      }
    ASSERT_NEAR(response.response[n], best, 1e-12) << "vertex " << n;
    if (best > 1e-9) {
      EXPECT_NEAR(response.corner_angle[n], best_angle, 1e-12) << "vertex " << n;
      EXPECT_EQ(response.turn[n], best_turn) << "vertex " << n;
    }
    (best > 0.0 ? corners : straight) += 1;
  }
  EXPECT_GT(straight, 100);  // both kinds of window were met
  EXPECT_GT(corners, 100);
}

TEST(MatchedFilter, StraightLineGivesNoResponse) {
  const EqualizedContour line = equalizeByStep({{0, 0}, {3, 1}}, 0.05);
  const CornerResponse response = filterCorners(line, CornerFilterParams{});
  for (double c : response.response) EXPECT_NEAR(c, 0.0, 1e-12);
}

TEST(MatchedFilter, ShortContourGivesZeros) {
  const EqualizedContour tiny = equalizeByStep({{0, 0}, {0.2, 0}}, 0.05);
  const CornerResponse response = filterCorners(tiny, CornerFilterParams{});
  EXPECT_EQ(response.response.size(), tiny.vertices.size());
  for (double c : response.response) EXPECT_EQ(c, 0.0);
}

TEST(MatchedFilter, ValidateRejectsBadBanks) {
  CornerFilterParams params;
  params.corner_angles_deg = {};
  EXPECT_FALSE(params.validate());
  params.corner_angles_deg = {180.0};
  EXPECT_FALSE(params.validate());
  params = CornerFilterParams{};
  params.arm_elements = 1;
  EXPECT_FALSE(params.validate());
}

}  // namespace
}  // namespace contour_reg
