#include "contour_reg/core/transform_estimation.h"

#include <cmath>

#include <Eigen/Dense>

namespace contour_reg {

namespace {

// The rigid transform of rotation (cos, sin) = (c, s) and translation t.
Eigen::Matrix3d rotationFrom(double c, double s, const Eigen::Vector2d &t) {
  Eigen::Matrix3d rigid = Eigen::Matrix3d::Identity();
  rigid.topLeftCorner<2, 2>() << c, -s, s, c;
  rigid.topRightCorner<2, 1>() = t;
  return rigid;
}

}  // namespace

// Eq. (17): the normal equations of x' = a x + b y + c, y' = d x + e y + f. Both rows
// share the matrix M = sum [x y 1]^T [x y 1].
bool estimateAffine(const Points2D &source, const Points2D &target, Eigen::Matrix3d &transform) {
  if (source.size() < 3 || source.size() != target.size()) return false;
  Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();
  Eigen::Vector3d rhs_x = Eigen::Vector3d::Zero(), rhs_y = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < source.size(); ++i) {
    const Eigen::Vector3d h(source[i].x(), source[i].y(), 1.0);
    normal += h * h.transpose();
    rhs_x += h * target[i].x();
    rhs_y += h * target[i].y();
  }
  // Collinear points make M singular: the affine map is then undetermined.
  Eigen::FullPivLU<Eigen::Matrix3d> lu(normal);
  lu.setThreshold(1e-9 * std::max(1.0, normal.cwiseAbs().maxCoeff()));
  if (lu.rank() < 3) return false;
  transform.setIdentity();
  transform.row(0) = lu.solve(rhs_x).transpose();
  transform.row(1) = lu.solve(rhs_y).transpose();
  return true;
}

bool estimateRigid(const Points2D &source, const Points2D &target, Eigen::Matrix3d &transform) {
  if (source.size() < 2 || source.size() != target.size()) return false;
  Eigen::Vector2d mean_p = Eigen::Vector2d::Zero(), mean_q = Eigen::Vector2d::Zero();
  for (std::size_t i = 0; i < source.size(); ++i) {
    mean_p += source[i];
    mean_q += target[i];
  }
  mean_p /= static_cast<double>(source.size());
  mean_q /= static_cast<double>(source.size());
  double dot = 0.0, cross = 0.0;
  for (std::size_t i = 0; i < source.size(); ++i) {
    const Eigen::Vector2d p = source[i] - mean_p, q = target[i] - mean_q;
    dot += p.dot(q);
    cross += p.x() * q.y() - p.y() * q.x();
  }
  const double norm = std::hypot(dot, cross);
  if (norm < 1e-12) return false;  // all points coincide
  // The rotation's cosine and sine are dot and cross, normalised: no angle needed.
  transform = rotationFrom(dot / norm, cross / norm, Eigen::Vector2d::Zero());
  transform.topRightCorner<2, 1>() = mean_q - transform.topLeftCorner<2, 2>() * mean_p;
  return true;
}

Eigen::Matrix3d rigidPart(const Eigen::Matrix3d &affine) {
  // The rotation nearest the linear part: (a00 + a11, a10 - a01), normalised, is its cosine and sine.
  const double c = affine(0, 0) + affine(1, 1), s = affine(1, 0) - affine(0, 1), norm = std::hypot(c, s);
  const Eigen::Vector2d translation = affine.topRightCorner<2, 1>();
  return norm == 0.0 ? rotationFrom(1.0, 0.0, translation) : rotationFrom(c / norm, s / norm, translation);
}

Eigen::Matrix3d rigidTransform(double x, double y, double yaw) {
  return rotationFrom(std::cos(yaw), std::sin(yaw), Eigen::Vector2d(x, y));
}

double yawOf(const Eigen::Matrix3d &transform) { return std::atan2(transform(1, 0), transform(0, 0)); }

Eigen::Matrix3d rigidInverse(const Eigen::Matrix3d &rigid) {
  Eigen::Matrix3d inverse = Eigen::Matrix3d::Identity();
  inverse.topLeftCorner<2, 2>() = rigid.topLeftCorner<2, 2>().transpose();
  inverse.topRightCorner<2, 1>() = -inverse.topLeftCorner<2, 2>() * rigid.topRightCorner<2, 1>();
  return inverse;
}

}  // namespace contour_reg
