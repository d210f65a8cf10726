#pragma once
/// @file closure.h
/// A covariance check that needs no reference: three registrations of scans a, b and c around
/// a triangle. With ab the motion of scan b in a's frame, bc of c in b's and ac of c in a's,
/// ac^-1 ab bc is the identity when all three are right; its departure, weighed by the three
/// covariances carried through the composition, is chi-square with 3 degrees of freedom
/// when the covariances are honest and the errors independent.
///
/// The three share scans (ab and ac see a, ab and bc see b, bc and ac see c): what one scan's
/// own noise does to two of them largely cancels around the triangle. A closure NEES above
/// its chi-square therefore shows over-confidence; one within it shows less about honesty.

#include <Eigen/Core>

#include "contour_reg/io/pose2d.h"

namespace contour_reg::evaluation {

/// The closure of one triangle: `error` is (x m, y m, yaw rad wrapped to [-pi, pi]) of
/// ac^-1 ab bc, `covariance` its first-order covariance from the three (in that order of
/// x, y, yaw), `nees` = error^T covariance^-1 error (infinite where it is singular).
struct TriangleClosure {
  Eigen::Vector3d error = Eigen::Vector3d::Zero();
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  double nees = 0.0;
};

TriangleClosure triangleClosure(const io::Pose2D &ab, const Eigen::Matrix3d &ab_covariance, const io::Pose2D &bc,
                                const Eigen::Matrix3d &bc_covariance, const io::Pose2D &ac,
                                const Eigen::Matrix3d &ac_covariance);

}  // namespace contour_reg::evaluation
