#include "contour_reg/evaluation/free_space_check.h"

#include <cmath>

#include "contour_reg/core/contour.h"
#include "contour_reg/core/transform_estimation.h"

namespace contour_reg::evaluation {

namespace {

struct Counts {
  int tested = 0, contradicted = 0;
};

// The returns of `points` (NaN: none) moved by `motion` against `view`.
void check(const ComplexSequence &points, const RangeView &view, const Eigen::Matrix3d &motion, double margin,
           Counts &counts) {
  for (const Complex &p : points) {
    if (!isFinite(p)) continue;
    const Eigen::Vector2d moved = transformPoint(motion, Eigen::Vector2d(p.real(), p.imag()));
    const RangeView::Sight sight = view.sightOf(moved, margin);
    if (sight == RangeView::Sight::kNoEvidence) continue;
    ++counts.tested;
    counts.contradicted += sight == RangeView::Sight::kSeenThrough;
  }
}

}  // namespace

FreeSpaceCheck::FreeSpaceCheck(const LaserScan &first, const LaserScan &second, double margin)
    : first_(polarCode(first)), second_(polarCode(second)), margin_(margin) {
  first_view_.assign(first_);
  second_view_.assign(second_);
}

double FreeSpaceCheck::contradictedShare(const Eigen::Matrix3d &second_to_first) const {
  Counts counts;
  check(second_, first_view_, second_to_first, margin_, counts);
  check(first_, second_view_, rigidInverse(second_to_first), margin_, counts);
  return counts.tested > 0 ? static_cast<double>(counts.contradicted) / counts.tested : 0.0;
}

}  // namespace contour_reg::evaluation
