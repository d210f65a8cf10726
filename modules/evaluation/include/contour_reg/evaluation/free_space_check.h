#pragma once
/// @file free_space_check.h
/// Whether a relative motion agrees with the two scans it relates, by their free space.
///
/// A LIDAR beam that returns at range r saw empty space up to r (core/free_space.h). A right
/// motion puts few returns of either scan where the other scan's beams passed through empty
/// space: a walking person, a door moved, a pane of glass. A wrong motion puts walls there,
/// whether it is a registration's estimate or a reference's. Checked for the estimate and for
/// the reference of the same pair, this tells a registration's failure from an error of the
/// reference: the corrected poses of the Radish logs are GMapping's, which has some.
///
/// Every return of both scans is checked, beam by beam, isolated returns (posts, trunks)
/// included, against the two beams of the other scan that bracket its bearing.

#include <Eigen/Core>

#include "contour_reg/core/free_space.h"
#include "contour_reg/core/laser_scan.h"

namespace contour_reg::evaluation {

/// Shares of free-space contradiction that differ by less than this are the same evidence.
constexpr double kFreeSpaceShareTie = 0.05;

/// The views of two scans, for checking motions between them.
class FreeSpaceCheck {
 public:
  /// `margin` m: how far in front of the other scan's measured range a return must lie to
  /// contradict (FreeSpaceParams::margin).
  FreeSpaceCheck(const LaserScan &first, const LaserScan &second, double margin = FreeSpaceParams{}.margin);

  /// The share of the returns of both scans, among those inside the other scan's view, that
  /// `second_to_first` (the second scan's pose in the first's frame) puts in the other scan's
  /// free space. 0 when no return falls inside the other's view.
  double contradictedShare(const Eigen::Matrix3d &second_to_first) const;

 private:
  ComplexSequence first_, second_;
  RangeView first_view_, second_view_;
  double margin_;
};

}  // namespace contour_reg::evaluation
