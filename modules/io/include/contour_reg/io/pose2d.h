#pragma once
/// @file pose2d.h
/// Planar poses as homogeneous 3x3 matrices: composition and relative motion.

#include <cmath>

#include <Eigen/Core>

#include "contour_reg/io/scan_log.h"

namespace contour_reg::io {

inline Eigen::Matrix3d toMatrix(const Pose2D &p) {
  Eigen::Matrix3d m = Eigen::Matrix3d::Identity();
  m(0, 0) = m(1, 1) = std::cos(p.yaw);
  m(1, 0) = std::sin(p.yaw);
  m(0, 1) = -m(1, 0);
  m(0, 2) = p.x;
  m(1, 2) = p.y;
  return m;
}

inline Pose2D toPose(const Eigen::Matrix3d &m) { return {m(0, 2), m(1, 2), std::atan2(m(1, 0), m(0, 0))}; }

/// The pose of `b` seen from `a`: a^-1 b.
inline Pose2D between(const Pose2D &a, const Pose2D &b) {
  const double c = std::cos(a.yaw), s = std::sin(a.yaw), dx = b.x - a.x, dy = b.y - a.y;
  return {c * dx + s * dy, -s * dx + c * dy, std::remainder(b.yaw - a.yaw, 2.0 * M_PI)};
}

/// `a` followed by the motion `delta` expressed in a's frame: a * delta.
inline Pose2D compose(const Pose2D &a, const Pose2D &delta) { return toPose(toMatrix(a) * toMatrix(delta)); }

/// The motion `delta` scaled by s (translation and yaw alike): for constant-velocity prediction.
inline Pose2D scaled(const Pose2D &delta, double s) { return {delta.x * s, delta.y * s, delta.yaw * s}; }

}  // namespace contour_reg::io
