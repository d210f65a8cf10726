#pragma once
/// @file point_to_line_icp.h
/// Point-to-line ICP for planar scans (PL-ICP, the standard 2-D baseline of CSM and
/// laser_scan_matcher) as one pcl::Registration on plain points: PCL's
/// IterativeClosestPointWithNormals with TransformationEstimationPointToLine2D, the target's
/// normals fitted to each point's nearest neighbours in the plane.

#include <cmath>

#include <pcl/common/transforms.h>
#include <pcl/point_types.h>
#include <pcl/registration/icp.h>
#include <pcl/registration/registration.h>
#include <pcl/search/kdtree.h>
#include <Eigen/Eigenvalues>

#include "contour_reg/transformation_estimation_point_to_line_2d.h"

namespace contour_reg {

/// align() fits a line to every target point's setNormalNeighbours() nearest neighbours (the
/// point itself included; NaN points are left out), then runs ICP whose error is each source
/// point's distance to the line through its closest target point. The target's normals are
/// fitted once per setInputTarget(). setMaximumIterations(), setMaxCorrespondenceDistance(),
/// setTransformationEpsilon() and setEuclideanFitnessEpsilon() are passed on to the ICP.
/// Defaults: 5 neighbours, 1 m correspondence distance, 50 iterations, 1e-8 epsilons.
template <typename PointSource, typename PointTarget, typename Scalar = float>
class PointToLineIcp : public pcl::Registration<PointSource, PointTarget, Scalar> {
 public:
  using Base = pcl::Registration<PointSource, PointTarget, Scalar>;
  using Ptr = std::shared_ptr<PointToLineIcp<PointSource, PointTarget, Scalar>>;
  using typename Base::Matrix4;
  using typename Base::PointCloudSource;
  using typename Base::PointCloudTargetConstPtr;
  using Cloud = pcl::PointCloud<pcl::PointNormal>;
  using Icp = pcl::IterativeClosestPointWithNormals<pcl::PointNormal, pcl::PointNormal, Scalar>;

  PointToLineIcp() {
    this->reg_name_ = "PointToLineIcp";
    this->setMaximumIterations(50);
    this->setMaxCorrespondenceDistance(1.0);
    this->setTransformationEpsilon(1e-8);
    this->setEuclideanFitnessEpsilon(1e-8);
    icp_->setTransformationEstimation(
        pcl::make_shared<TransformationEstimationPointToLine2D<pcl::PointNormal, pcl::PointNormal, Scalar>>());
  }

  /// Neighbours (the point included) each target normal is fitted to; at least 2.
  void setNormalNeighbours(int k) { neighbours_ = std::max(2, k); }
  int getNormalNeighbours() const { return neighbours_; }

  void setInputTarget(const PointCloudTargetConstPtr &cloud) override {
    Base::setInputTarget(cloud);
    target_lines_.reset();
  }

 protected:
  void computeTransformation(PointCloudSource &output, const Matrix4 &guess) override {
    if (!target_lines_) {  // a new target: its lines, indexed once for every source aligned to it
      target_lines_ = withLineNormals(finitePoints(*this->target_));
      if (target_lines_->size() >= 3) icp_->setInputTarget(target_lines_);
    }
    const typename Cloud::Ptr source = finitePoints(*this->input_);  // the error uses the target's normals only
    this->converged_ = false;
    this->final_transformation_ = guess;
    if (target_lines_->size() >= 3 && source->size() >= 3) {
      icp_->setInputSource(source);
      icp_->setMaximumIterations(this->max_iterations_);
      icp_->setMaxCorrespondenceDistance(std::sqrt(this->corr_dist_threshold_));
      icp_->setTransformationEpsilon(this->transformation_epsilon_);
      icp_->setEuclideanFitnessEpsilon(this->euclidean_fitness_epsilon_);
      Cloud aligned;
      icp_->align(aligned, guess);
      this->converged_ = icp_->hasConverged();
      if (this->converged_) this->final_transformation_ = icp_->getFinalTransformation();
    }
    this->transformation_ = this->final_transformation_;
    pcl::transformPointCloud(*this->input_, output, this->final_transformation_);
  }

 private:
  // The finite points in the plane (z 0, normals 0).
  template <typename Point>
  static typename Cloud::Ptr finitePoints(const pcl::PointCloud<Point> &points) {
    auto cloud = pcl::make_shared<Cloud>();
    cloud->reserve(points.size());
    for (const Point &p : points)
      if (std::isfinite(p.x) && std::isfinite(p.y)) {
        pcl::PointNormal q;
        q.x = p.x;
        q.y = p.y;
        q.z = q.normal_x = q.normal_y = q.normal_z = 0.f;
        cloud->push_back(q);
      }
    return cloud;
  }

  // The points, each with the normal of the line through its nearest neighbours in the plane;
  // all of them are left out when there are fewer points than neighbours.
  typename Cloud::Ptr withLineNormals(const typename Cloud::Ptr &cloud) const {
    auto lines = pcl::make_shared<Cloud>();
    if (cloud->size() < static_cast<std::size_t>(neighbours_)) return lines;
    pcl::search::KdTree<pcl::PointNormal> tree;
    tree.setInputCloud(cloud);
    pcl::Indices found;
    std::vector<float> distances;
    for (const pcl::PointNormal &p : *cloud) {
      if (tree.nearestKSearch(p, neighbours_, found, distances) < neighbours_) continue;
      Eigen::Vector2d mean = Eigen::Vector2d::Zero();
      for (const auto index : found) mean += Eigen::Vector2d((*cloud)[index].x, (*cloud)[index].y);
      mean /= double(found.size());
      Eigen::Matrix2d scatter = Eigen::Matrix2d::Zero();
      for (const auto index : found) {
        const Eigen::Vector2d d = Eigen::Vector2d((*cloud)[index].x, (*cloud)[index].y) - mean;
        scatter += d * d.transpose();
      }
      const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen(scatter);
      pcl::PointNormal q = p;
      q.normal_x = float(eigen.eigenvectors()(0, 0));  // the direction of least spread
      q.normal_y = float(eigen.eigenvectors()(1, 0));
      q.normal_z = 0.f;
      lines->push_back(q);
    }
    return lines;
  }

  typename Icp::Ptr icp_ = pcl::make_shared<Icp>();
  typename Cloud::Ptr target_lines_;
  int neighbours_ = 5;
};

}  // namespace contour_reg
