#pragma once

#include <pcl/common/transforms.h>
#include <pcl/console/print.h>

#include "contour_reg/contour_registration.h"
#include "contour_reg/lazy_kdtree.h"

namespace contour_reg {

namespace detail {

template <typename PointT>
bool hasFinitePoint(const pcl::PointCloud<PointT> &cloud) {
  for (const PointT &p : cloud)
    if (std::isfinite(p.x) && std::isfinite(p.y)) return true;
  return false;
}

}  // namespace detail

template <typename PointSource, typename PointTarget, typename Scalar>
ContourRegistration<PointSource, PointTarget, Scalar>::ContourRegistration() {
  reg_name_ = "ContourRegistration";
  this->tree_.reset(new LazyKdTree<PointTarget>());
  this->max_iterations_ = params_.ransac.max_iterations;
}

template <typename PointSource, typename PointTarget, typename Scalar>
void ContourRegistration<PointSource, PointTarget, Scalar>::setInputSource(const PointCloudSourceConstPtr &cloud) {
  source_ready_ = false;
  if (cloud && cloud->empty()) {
    // pcl::Registration would keep the previous source; align() must fail on this one instead.
    PCL_ERROR("[contour_reg::%s::setInputSource] Empty source cloud.\n", getClassName().c_str());
    input_ = cloud;
    return;
  }
  Base::setInputSource(cloud);
}

template <typename PointSource, typename PointTarget, typename Scalar>
void ContourRegistration<PointSource, PointTarget, Scalar>::setInputTarget(const PointCloudTargetConstPtr &cloud) {
  const bool same_as_target = target_ready_ && cloud == target_;
  if (cloud && cloud->empty()) {
    PCL_ERROR("[contour_reg::%s::setInputTarget] Empty target cloud.\n", getClassName().c_str());
    target_ = cloud;
    this->target_cloud_updated_ = true;
    target_ready_ = false;
    return;
  }
  Base::setInputTarget(cloud);
  if (same_as_target) return;
  // Odometry: the new target is the cloud that was the source of the last align().
  if (source_ready_ && static_cast<const void *>(cloud.get()) == source_cloud_) {
    std::swap(target_features_, source_features_);  // the next source is a new cloud
    source_ready_ = false;
    source_cloud_ = nullptr;
    target_ready_ = true;
    return;
  }
  target_ready_ = false;
}

template <typename PointSource, typename PointTarget, typename Scalar>
void ContourRegistration<PointSource, PointTarget, Scalar>::setContourParams(const ContourParams &params) {
  contour_params_ = params;
  source_ready_ = target_ready_ = false;
}

template <typename PointSource, typename PointTarget, typename Scalar>
void ContourRegistration<PointSource, PointTarget, Scalar>::computeTransformation(PointCloudSource &output,
                                                                                const Matrix4 &guess) {
  const Matrix4 fallback = guess;
  final_transformation_ = transformation_ = fallback;
  converged_ = false;
  nr_iterations_ = 0;
  std::string why;
  if (!contour_params_.validate(&why) || !params_.validate(&why)) {
    result_ = RegistrationResult{};
    PCL_ERROR("[contour_reg::%s::computeTransformation] Invalid parameters: %s.\n", getClassName().c_str(), why.c_str());
    result_.status = RegistrationStatus::kInvalidParameters;
    result_.reason = why;
    return;
  }
  if (!detail::hasFinitePoint(*input_) || !detail::hasFinitePoint(*target_)) {
    result_ = RegistrationResult{};
    result_.reason = !detail::hasFinitePoint(*input_) ? "source cloud has no valid point" : "target cloud has no valid point";
    PCL_ERROR("[contour_reg::%s::computeTransformation] %s.\n", getClassName().c_str(), result_.reason.c_str());
    result_.status = RegistrationStatus::kTooFewSpecialPoints;
    return;
  }
  if (!source_ready_) {
    extractContourFeatures(*input_, contour_params_, source_features_);
    source_cloud_ = input_.get();
    source_ready_ = true;
  }
  if (!target_ready_) {
    extractContourFeatures(*target_, contour_params_, target_features_);
    target_ready_ = true;
  }

  // The planar part of the guess, source to target.
  Eigen::Matrix3d guess2d = Eigen::Matrix3d::Identity();
  guess2d.topLeftCorner<2, 2>() = guess.template topLeftCorner<2, 2>().template cast<double>();
  guess2d.topRightCorner<2, 1>() = guess.template block<2, 1>(0, 3).template cast<double>();
  guess2d = rigidPart(guess2d);

  rng_.seed(seed_);
  registerContours(source_features_, target_features_, params_, rng_, &guess2d, buffers_, result_);
  nr_iterations_ = result_.ransac_iterations;
  converged_ = result_.converged;
  if (!converged_) {
    PCL_DEBUG("[contour_reg::%s::computeTransformation] Not converged: %s.\n", getClassName().c_str(),
              result_.reason.c_str());
    pcl::transformPointCloud(output, output, final_transformation_);
    return;
  }
  Matrix4 transform = Matrix4::Identity();
  transform.template topLeftCorner<2, 2>() = result_.transform.topLeftCorner<2, 2>().template cast<Scalar>();
  transform.template block<2, 1>(0, 3) = result_.transform.topRightCorner<2, 1>().template cast<Scalar>();
  final_transformation_ = transformation_ = transform;
  pcl::transformPointCloud(output, output, final_transformation_);
}

}  // namespace contour_reg
