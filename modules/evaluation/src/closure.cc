#include "contour_reg/evaluation/closure.h"

#include <cmath>

#include <Eigen/Geometry>

#include "contour_reg/evaluation/metrics.h"

namespace contour_reg::evaluation {

TriangleClosure triangleClosure(const io::Pose2D &ab, const Eigen::Matrix3d &ab_covariance, const io::Pose2D &bc,
                                const Eigen::Matrix3d &bc_covariance, const io::Pose2D &ac,
                                const Eigen::Matrix3d &ac_covariance) {
  // ac^-1 ab bc: translation R_ac^T (t_ab + R_ab t_bc - t_ac), yaw ab + bc - ac.
  const io::Pose2D departure = io::between(ac, io::compose(ab, bc));
  const Eigen::Vector2d t(departure.x, departure.y), t_bc(bc.x, bc.y);
  const Eigen::Matrix2d r_ab = Eigen::Rotation2Dd(ab.yaw).toRotationMatrix();
  const Eigen::Matrix2d r_ac_t = Eigen::Rotation2Dd(-ac.yaw).toRotationMatrix();
  const Eigen::Matrix2d turn = (Eigen::Matrix2d() << 0.0, -1.0, 1.0, 0.0).finished();  // d R(yaw) / d yaw = turn R

  // Its derivatives by each motion's (x, y, yaw).
  Eigen::Matrix3d by_ab = Eigen::Matrix3d::Zero(), by_bc = Eigen::Matrix3d::Zero(), by_ac = Eigen::Matrix3d::Zero();
  by_ab.topLeftCorner<2, 2>() = r_ac_t;
  by_ab.topRightCorner<2, 1>() = r_ac_t * turn * r_ab * t_bc;
  by_ab(2, 2) = 1.0;
  by_bc.topLeftCorner<2, 2>() = r_ac_t * r_ab;
  by_bc(2, 2) = 1.0;
  by_ac.topLeftCorner<2, 2>() = -r_ac_t;
  by_ac.topRightCorner<2, 1>() = -turn * t;
  by_ac(2, 2) = -1.0;

  TriangleClosure closure;
  closure.error << t, std::remainder(departure.yaw, 2.0 * M_PI);
  closure.covariance = by_ab * ab_covariance * by_ab.transpose() + by_bc * bc_covariance * by_bc.transpose() +
                       by_ac * ac_covariance * by_ac.transpose();
  closure.covariance = 0.5 * (closure.covariance + closure.covariance.transpose());
  closure.nees = normalisedErrorSquared(departure, io::Pose2D{}, closure.covariance, 0.0, 0.0);
  return closure;
}

}  // namespace contour_reg::evaluation
