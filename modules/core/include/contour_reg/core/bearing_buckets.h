#pragma once
/// @file bearing_buckets.h
/// Search by bearing in a scan's points sorted by bearing, in constant time.
///
/// Buckets of equal width over [-pi, pi) keep the first point at or above each bucket's lower
/// edge, so a search starts a few points before its answer instead of bisecting the scan. Used
/// by the refinement's projective search and the free-space view.

#include <algorithm>
#include <cmath>
#include <vector>

namespace contour_reg {

class BearingBuckets {
 public:
  /// Indexes `bearings` (rad, ascending), with `per_point` buckets per bearing on average.
  void build(const std::vector<double> &bearings, long per_point) {
    const long buckets = per_point * static_cast<long>(bearings.size()) + 1;
    per_rad_ = static_cast<double>(buckets) / (2.0 * M_PI);
    first_.resize(static_cast<std::size_t>(buckets));
    long first = 0;
    for (long k = 0; k < buckets; ++k) {
      const double edge = -M_PI + static_cast<double>(k) / per_rad_;
      while (first < static_cast<long>(bearings.size()) && bearings[first] < edge) ++first;
      first_[k] = first;
    }
  }

  /// The first of `bearings` (those indexed) at or above b, bearings.size() when none: the
  /// answer of std::lower_bound.
  long firstAtOrAbove(const std::vector<double> &bearings, double b) const {
    if (first_.empty()) return 0;
    const double at = (b + M_PI) * per_rad_;
    const long last = static_cast<long>(first_.size()) - 1;
    // Clamped before the conversion, which is undefined out of range; NaN: bucket 0.
    const long k = at >= static_cast<double>(last) ? last : at >= 0.0 ? static_cast<long>(at) : 0;
    return firstAtOrAboveFrom(bearings, b, first_[k]);  // b may have rounded into the next bucket
  }

  /// The same, walked to from `from`, the answer for a bearing near b: a step or two for a
  /// bearing that moved a little, without the buckets.
  static long firstAtOrAboveFrom(const std::vector<double> &bearings, double b, long from) {
    const long size = static_cast<long>(bearings.size());
    long j = std::min(std::max(from, 0L), size);
    while (j > 0 && bearings[j - 1] >= b) --j;
    while (j < size && bearings[j] < b) ++j;
    return j;
  }

 private:
  std::vector<long> first_;
  double per_rad_ = 0.0;
};

}  // namespace contour_reg
