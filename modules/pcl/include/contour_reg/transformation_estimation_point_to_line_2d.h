#pragma once
/// @file transformation_estimation_point_to_line_2d.h
/// The planar point-to-line error of PL-ICP (Censi 2008; CSM) as a PCL transformation
/// estimation: the motion (x, y, yaw) that minimises the squared distances of the source
/// points to the lines through their target points along the target normals, linearised in
/// the yaw and solved in closed form. PCL's TransformationEstimationPointToPlaneLLS solves the
/// same in 6-D, which a planar scan (normals without z, points at z = 0) leaves singular.

#include <cmath>

#include <pcl/correspondence.h>
#include <pcl/point_cloud.h>
#include <pcl/registration/transformation_estimation.h>
#include <Eigen/Cholesky>
#include <Eigen/Core>

namespace contour_reg {

/// PointTarget must carry normal_x and normal_y (pcl::PointNormal); z and normal_z are ignored.
template <typename PointSource, typename PointTarget, typename Scalar = float>
class TransformationEstimationPointToLine2D
    : public pcl::registration::TransformationEstimation<PointSource, PointTarget, Scalar> {
 public:
  using Ptr = std::shared_ptr<TransformationEstimationPointToLine2D<PointSource, PointTarget, Scalar>>;
  using Matrix4 = typename pcl::registration::TransformationEstimation<PointSource, PointTarget, Scalar>::Matrix4;

  void estimateRigidTransformation(const pcl::PointCloud<PointSource> &source,
                                   const pcl::PointCloud<PointTarget> &target, Matrix4 &transform) const override {
    Normal system;
    for (std::size_t k = 0; k < std::min(source.size(), target.size()); ++k) system.add(source[k], target[k]);
    transform = system.solve();
  }
  void estimateRigidTransformation(const pcl::PointCloud<PointSource> &source, const pcl::Indices &source_indices,
                                   const pcl::PointCloud<PointTarget> &target, Matrix4 &transform) const override {
    Normal system;
    for (std::size_t k = 0; k < std::min(source_indices.size(), target.size()); ++k)
      system.add(source[source_indices[k]], target[k]);
    transform = system.solve();
  }
  void estimateRigidTransformation(const pcl::PointCloud<PointSource> &source, const pcl::Indices &source_indices,
                                   const pcl::PointCloud<PointTarget> &target, const pcl::Indices &target_indices,
                                   Matrix4 &transform) const override {
    Normal system;
    for (std::size_t k = 0; k < std::min(source_indices.size(), target_indices.size()); ++k)
      system.add(source[source_indices[k]], target[target_indices[k]]);
    transform = system.solve();
  }
  void estimateRigidTransformation(const pcl::PointCloud<PointSource> &source,
                                   const pcl::PointCloud<PointTarget> &target,
                                   const pcl::Correspondences &correspondences, Matrix4 &transform) const override {
    Normal system;
    for (const pcl::Correspondence &c : correspondences) system.add(source[c.index_query], target[c.index_match]);
    transform = system.solve();
  }

 private:
  // The normal equations in (x, y, yaw): each pair adds the row (n, p x n) and the
  // right-hand side (q - p) . n, with p the source point, q and n the target point and normal.
  struct Normal {
    Eigen::Matrix3d ata = Eigen::Matrix3d::Zero();
    Eigen::Vector3d atb = Eigen::Vector3d::Zero();
    void add(const PointSource &p, const PointTarget &q) {
      const double nx = q.normal_x, ny = q.normal_y;
      if (!std::isfinite(nx) || !std::isfinite(ny) || !std::isfinite(p.x) || !std::isfinite(p.y)) return;
      const Eigen::Vector3d row(nx, ny, double(p.x) * ny - double(p.y) * nx);
      ata += row * row.transpose();
      atb += row * ((double(q.x) - p.x) * nx + (double(q.y) - p.y) * ny);
    }
    Matrix4 solve() const {
      Matrix4 transform = Matrix4::Identity();
      // A direction no pair constrains (a corridor's axis) stays where it is: the damping
      // keeps the solve finite and moves nothing along it.
      const Eigen::Vector3d x = (ata + 1e-9 * (ata.trace() + 1.0) * Eigen::Matrix3d::Identity()).ldlt().solve(atb);
      if (!x.allFinite()) return transform;
      const double c = std::cos(x.z()), s = std::sin(x.z());
      transform(0, 0) = Scalar(c);
      transform(0, 1) = Scalar(-s);
      transform(1, 0) = Scalar(s);
      transform(1, 1) = Scalar(c);
      transform(0, 3) = Scalar(x.x());
      transform(1, 3) = Scalar(x.y());
      return transform;
    }
  };
};

}  // namespace contour_reg
