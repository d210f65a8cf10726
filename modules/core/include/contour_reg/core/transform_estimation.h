#pragma once
/// @file transform_estimation.h
/// Stage E: the transform between paired points (paper eqs. 15-17).
///
/// Transforms are 3x3 homogeneous matrices H with q = H p (source point p, target point
/// q). The paper fits the affine map x' = a x + b y + c, y' = d x + e y + f by least
/// squares through its normal equations (eq. 17, at least 3 pairs). A robot's motion is
/// rigid, so the closed-form rigid SE(2) fit (at least 2 pairs) is offered too, and the
/// rigid part of an affine fit can be taken.

#include <vector>

#include <Eigen/Core>

namespace contour_reg {

using Points2D = std::vector<Eigen::Vector2d>;

/// Least-squares affine map from `source` to `target` (eq. 17); false when the
/// points are too few or collinear.
bool estimateAffine(const Points2D &source, const Points2D &target, Eigen::Matrix3d &transform);

/// Least-squares rigid map (rotation and translation); false when fewer than 2 points
/// or all coincide.
bool estimateRigid(const Points2D &source, const Points2D &target, Eigen::Matrix3d &transform);

/// The rotation and translation nearest to an affine map (the rotation closest in
/// Frobenius norm to its linear part).
Eigen::Matrix3d rigidPart(const Eigen::Matrix3d &affine);

/// A rigid transform from x, y (m) and yaw (rad).
Eigen::Matrix3d rigidTransform(double x, double y, double yaw);

/// The inverse of a rigid transform (rotation transposed, translation turned back).
Eigen::Matrix3d rigidInverse(const Eigen::Matrix3d &rigid);

/// The yaw of a rigid (or nearly rigid) transform.
double yawOf(const Eigen::Matrix3d &transform);

/// The point `p` moved by `transform`: H p.
inline Eigen::Vector2d transformPoint(const Eigen::Matrix3d &transform, const Eigen::Vector2d &p) {
  return transform.topLeftCorner<2, 2>() * p + transform.topRightCorner<2, 1>();
}

}  // namespace contour_reg
