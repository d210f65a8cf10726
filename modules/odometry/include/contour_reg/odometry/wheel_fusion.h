#pragma once
/// @file wheel_fusion.h
/// Wheel odometry as a prior: the scans' motion and the wheels' motion between two scans, each
/// with its uncertainty, fused into one estimate.
///
/// Both measure the same increment (x, y in metres, yaw in radians, in the earlier scan's
/// frame). The fused increment is their information-weighted mean, taken in the tangent space
/// at the scans' motion (the yaw difference wrapped):
///   x = s + (S + W)^-1 W (w - s),   covariance (S + W)^-1,
/// with S the scans' information and W the wheels'. Where the scans are sure (a room) they
/// decide; along a direction they leave free (a corridor's axis, where S is zero: see
/// PinnedMotion) the wheels decide.
///
/// The wheels' covariance is the odometry motion model of Probabilistic Robotics (Thrun,
/// Burgard, Fox, sec. 5.4), as AMCL's odom_alpha1-4 set it: the increment as a turn r1 onto the
/// direction of travel, a drive t and a turn r2, each with a variance that grows with the
/// motion, carried to (x, y, yaw) by the Jacobian; plus a floor, so that a standing robot's zero
/// increment is not taken as exact.

#include <optional>
#include <string>

#include <Eigen/Core>

#include "contour_reg/io/scan_log.h"

namespace contour_reg::odometry {

/// The wheels' error model (Probabilistic Robotics' alpha1-4). The defaults maximise the
/// likelihood of the wheel odometry of the intel, fr079 and mit-csail logs against their
/// reference relations up to 1.5 s apart (2243 relations, the reference's own 2 cm / 0.5 deg
/// added; docs/results.md).
struct WheelNoise {
  double rotation_per_rotation = 0.07;        ///< alpha1, rad^2 of variance per rad^2 of turn
  double rotation_per_translation = 0.001;    ///< alpha2, rad^2 of variance per m^2 driven
  double translation_per_translation = 0.04;  ///< alpha3, m^2 of variance per m^2 driven
  double translation_per_rotation = 0.0007;   ///< alpha4, m^2 of variance per rad^2 of turn
  double translation_floor = 0.015;           ///< m, standard deviation per axis of any increment
  double rotation_floor = 0.02;               ///< rad, standard deviation of any increment

  bool validate(std::string *why = nullptr) const;
};

/// The covariance of a wheel increment (x, y, yaw) under `noise`.
Eigen::Matrix3d wheelCovariance(const io::Pose2D &increment, const WheelNoise &noise);

struct FusedMotion {
  io::Pose2D motion;
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  /// How far the two disagree: the fused motion's cost under both, (x - s)^T S (x - s) +
  /// (x - w)^T W (x - w), chi-square with as many degrees of freedom as the scans pin.
  double disagreement = 0.0;
};

/// The information-weighted mean of the scans' motion (information `scan_information`, which
/// may be zero along a free direction) and the wheels' (covariance `wheel_covariance`, positive
/// definite). None when the two together do not pin every direction, or a number is not
/// finite (a corrupt wheel sample of 1e300 m has a covariance of 1e600).
std::optional<FusedMotion> fuse(const io::Pose2D &scan, const Eigen::Matrix3d &scan_information,
                                const io::Pose2D &wheel, const Eigen::Matrix3d &wheel_covariance);

}  // namespace contour_reg::odometry
