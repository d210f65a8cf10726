#include "contour_reg/evaluation/closure.h"

#include <cmath>
#include <limits>

#include <Eigen/Dense>

namespace contour_reg::evaluation {

namespace {

Eigen::Matrix2d rotation(double yaw) {
  const double c = std::cos(yaw), s = std::sin(yaw);
  return (Eigen::Matrix2d() << c, -s, s, c).finished();
}

}  // namespace

TriangleClosure triangleClosure(const io::Pose2D &ab, const Eigen::Matrix3d &ab_covariance, const io::Pose2D &bc,
                                const Eigen::Matrix3d &bc_covariance, const io::Pose2D &ac,
                                const Eigen::Matrix3d &ac_covariance) {
  // ac^-1 ab bc: translation R_ac^T (t_ab + R_ab t_bc - t_ac), yaw ab + bc - ac.
  const Eigen::Matrix2d r_ab = rotation(ab.yaw), r_ac_t = rotation(ac.yaw).transpose();
  const Eigen::Vector2d t_ab(ab.x, ab.y), t_bc(bc.x, bc.y), t_ac(ac.x, ac.y);
  const Eigen::Vector2d t = r_ac_t * (t_ab + r_ab * t_bc - t_ac);
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
  closure.error << t, std::remainder(ab.yaw + bc.yaw - ac.yaw, 2.0 * M_PI);
  closure.covariance = by_ab * ab_covariance * by_ab.transpose() + by_bc * bc_covariance * by_bc.transpose() +
                       by_ac * ac_covariance * by_ac.transpose();
  closure.covariance = 0.5 * (closure.covariance + closure.covariance.transpose());
  const Eigen::LDLT<Eigen::Matrix3d> ldlt(closure.covariance);
  closure.nees = ldlt.info() == Eigen::Success && ldlt.vectorD().minCoeff() > 0.0
                     ? closure.error.dot(ldlt.solve(closure.error))
                     : std::numeric_limits<double>::infinity();
  return closure;
}

}  // namespace contour_reg::evaluation
