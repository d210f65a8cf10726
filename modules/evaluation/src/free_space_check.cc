#include "contour_reg/evaluation/free_space_check.h"

#include "contour_reg/core/contour.h"

namespace contour_reg::evaluation {

FreeSpaceCheck::FreeSpaceCheck(const LaserScan &first, const LaserScan &second, double margin)
    : first_(polarCode(first)), second_(polarCode(second)), margin_(margin) {
  first_view_.assign(first_);
  second_view_.assign(second_);
}

double FreeSpaceCheck::contradictedShare(const Eigen::Matrix3d &second_to_first) const {
  return contradictedReturnShare(second_, first_view_, first_, second_view_, second_to_first, margin_);
}

}  // namespace contour_reg::evaluation
