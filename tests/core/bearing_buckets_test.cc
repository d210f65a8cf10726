#include "contour_reg/core/bearing_buckets.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace contour_reg {
namespace {

long lowerBound(const std::vector<double> &bearings, double b) {
  return std::lower_bound(bearings.begin(), bearings.end(), b) - bearings.begin();
}

// Every query answered as std::lower_bound answers it: at each bearing, one representable
// number either side of it, between and far beyond them, infinite and NaN.
void expectLowerBound(const std::vector<double> &bearings, long per_point) {
  BearingBuckets buckets;
  buckets.build(bearings, per_point);
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> queries = {-4.0, -M_PI, M_PI,  4.0,   0.0, std::numeric_limits<double>::quiet_NaN(),
                                 inf,  -inf,  1e300, -1e300};
  for (double b : bearings) {
    queries.push_back(b);
    queries.push_back(std::nextafter(b, -10.0));
    queries.push_back(std::nextafter(b, 10.0));
  }
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> anywhere(-M_PI - 0.1, M_PI + 0.1);
  for (int k = 0; k < 2000; ++k) queries.push_back(anywhere(rng));
  for (double q : queries) EXPECT_EQ(buckets.firstAtOrAbove(bearings, q), lowerBound(bearings, q)) << "bearing " << q;
}

TEST(BearingBuckets, AnswersAsLowerBoundOnAScan) {
  std::vector<double> beams;  // a 270 deg scan, 0.25 deg apart
  for (int k = 0; k <= 1080; ++k) beams.push_back(-0.75 * M_PI + k * M_PI / 720.0);
  expectLowerBound(beams, 4);
  expectLowerBound(beams, 1);
}

TEST(BearingBuckets, AnswersAsLowerBoundOnClusteredAndRepeatedBearings) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> narrow(0.3, 0.31);
  std::vector<double> bearings;
  for (int k = 0; k < 300; ++k) bearings.push_back(narrow(rng));  // many in one bucket
  bearings.insert(bearings.end(), {-M_PI, -M_PI, 1.0, 1.0, 1.0, std::nextafter(M_PI, 0.0)});
  std::sort(bearings.begin(), bearings.end());
  expectLowerBound(bearings, 2);
}

TEST(BearingBuckets, AnswersAsLowerBoundOnBucketEdges) {
  // Bearings on the buckets' lower edges, -pi + k / (buckets / 2 pi), and one representable
  // number below each: a bearing just below an edge may round into the bucket above it.
  const long per_point = 4, pairs = 60, buckets = per_point * 2 * pairs + 1;
  const double per_rad = static_cast<double>(buckets) / (2.0 * M_PI);
  std::vector<double> bearings;
  for (long k = 1; k <= pairs; ++k) {
    const double edge = -M_PI + static_cast<double>(7 * k) / per_rad;
    bearings.push_back(std::nextafter(edge, -10.0));
    bearings.push_back(edge);
  }
  expectLowerBound(bearings, per_point);
}

TEST(BearingBuckets, AnEmptyIndexAnswersNone) {
  BearingBuckets buckets;
  const std::vector<double> none;
  EXPECT_EQ(buckets.firstAtOrAbove(none, 0.5), 0);
  buckets.build(none, 4);
  EXPECT_EQ(buckets.firstAtOrAbove(none, 0.5), 0);
}

}  // namespace
}  // namespace contour_reg
