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

/// The robot's motion when the laser mounted at `laser_pose` on it moves by `laser_motion`
/// (both motions in their own frame at the start): M m M^-1.
inline Pose2D robotMotion(const Pose2D &laser_motion, const Pose2D &laser_pose) {
  return compose(compose(laser_pose, laser_motion), between(laser_pose, Pose2D{}));
}

/// The laser's motion when the robot it is mounted on at `laser_pose` moves by `robot_motion`: M^-1 r M.
inline Pose2D laserMotion(const Pose2D &robot_motion, const Pose2D &laser_pose) {
  return compose(between(laser_pose, robot_motion), laser_pose);
}

/// The covariance (x, y, yaw) of robotMotion(m, laser_pose) from the covariance of the laser's
/// motion m, by the Jacobian of M m M^-1 at m: the translation turns with the mounting's yaw, and
/// an error in the turn moves the robot by the lever of the mounting's offset.
inline Eigen::Matrix3d robotCovariance(const Eigen::Matrix3d &laser_covariance, const Pose2D &laser_motion,
                                       const Pose2D &laser_pose) {
  const double c = std::cos(laser_pose.yaw), s = std::sin(laser_pose.yaw);
  const double cm = std::cos(laser_motion.yaw), sm = std::sin(laser_motion.yaw);
  // d/dyaw of (t_M - R(yaw) t_M) = -R(yaw) J t_M, J the quarter turn.
  const double jx = -laser_pose.y, jy = laser_pose.x;
  Eigen::Matrix3d jacobian;
  jacobian << c, -s, -(cm * jx - sm * jy), s, c, -(sm * jx + cm * jy), 0.0, 0.0, 1.0;
  return jacobian * laser_covariance * jacobian.transpose();
}

}  // namespace contour_reg::io
