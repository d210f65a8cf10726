#include "contour_reg/odometry/wheel_fusion.h"

#include <cmath>

#include <Eigen/Cholesky>

namespace contour_reg::odometry {

bool WheelNoise::validate(std::string *why) const {
  const bool ok = rotation_per_rotation >= 0.0 && rotation_per_translation >= 0.0 &&
                  translation_per_translation >= 0.0 && translation_per_rotation >= 0.0 && translation_floor > 0.0 &&
                  rotation_floor > 0.0 &&
                  std::isfinite(rotation_per_rotation + rotation_per_translation + translation_per_translation +
                                translation_per_rotation + translation_floor + rotation_floor);
  if (!ok && why) *why = "wheel noise: the four variances must be finite and >= 0, the two floors finite and > 0";
  return ok;
}

Eigen::Matrix3d wheelCovariance(const io::Pose2D &increment, const WheelNoise &noise) {
  // The increment as turn r1, drive t, turn r2; a drive backwards is a negative t.
  double t = std::hypot(increment.x, increment.y), r1 = 0.0;
  if (t > 1e-9) {
    r1 = increment.x >= 0.0 ? std::atan2(increment.y, increment.x) : std::atan2(-increment.y, -increment.x);
    if (increment.x < 0.0) t = -t;
  }
  const double r2 = std::remainder(increment.yaw - r1, 2.0 * M_PI);
  const double a1 = noise.rotation_per_rotation, a2 = noise.rotation_per_translation;
  const double a3 = noise.translation_per_translation, a4 = noise.translation_per_rotation;
  const Eigen::Vector3d variances(a3 * t * t + a4 * (r1 * r1 + r2 * r2),  // t
                                  a1 * r1 * r1 + a2 * t * t,              // r1
                                  a1 * r2 * r2 + a2 * t * t);             // r2
  // x = t cos r1, y = t sin r1, yaw = r1 + r2.
  Eigen::Matrix3d jacobian;
  jacobian << std::cos(r1), -t * std::sin(r1), 0.0, std::sin(r1), t * std::cos(r1), 0.0, 0.0, 1.0, 1.0;
  const double ft = noise.translation_floor * noise.translation_floor, fr = noise.rotation_floor * noise.rotation_floor;
  return jacobian * variances.asDiagonal() * jacobian.transpose() +
         Eigen::Vector3d(ft, ft, fr).asDiagonal().toDenseMatrix();
}

std::optional<FusedMotion> fuse(const io::Pose2D &scan, const Eigen::Matrix3d &scan_information,
                                const io::Pose2D &wheel, const Eigen::Matrix3d &wheel_covariance) {
  const bool finite = std::isfinite(scan.x + scan.y + scan.yaw + wheel.x + wheel.y + wheel.yaw) &&
                      scan_information.allFinite() && wheel_covariance.allFinite();
  if (!finite) return std::nullopt;  // a corrupt sample: its arithmetic would give NaN
  const Eigen::LLT<Eigen::Matrix3d> wheel_solver(wheel_covariance);
  if (wheel_solver.info() != Eigen::Success) return std::nullopt;
  const Eigen::Matrix3d wheel_information = wheel_solver.solve(Eigen::Matrix3d::Identity());
  const Eigen::LLT<Eigen::Matrix3d> solver(scan_information + wheel_information);
  if (solver.info() != Eigen::Success) return std::nullopt;
  const Eigen::Vector3d difference(wheel.x - scan.x, wheel.y - scan.y, std::remainder(wheel.yaw - scan.yaw, 2 * M_PI));
  const Eigen::Vector3d step = solver.solve(wheel_information * difference);
  FusedMotion fused;
  fused.motion = {scan.x + step(0), scan.y + step(1), std::remainder(scan.yaw + step(2), 2 * M_PI)};
  fused.covariance = solver.solve(Eigen::Matrix3d::Identity());
  const Eigen::Vector3d from_wheel = step - difference;
  fused.disagreement = step.dot(scan_information * step) + from_wheel.dot(wheel_information * from_wheel);
  return fused;
}

}  // namespace contour_reg::odometry
