#pragma once

#include <algorithm>
#include <cmath>
#include <type_traits>

#include <pcl/common/transforms.h>
#include <pcl/console/print.h>

#include "contour_reg/contour_registration.h"
#include "contour_reg/lazy_kdtree.h"

namespace contour_reg {

namespace detail {

// Whether the cloud (or the points `indices` name) has a point with finite x and y.
template <typename PointT>
bool hasFinitePoint(const pcl::PointCloud<PointT> &cloud, const pcl::Indices *indices = nullptr) {
  const auto finite = [](const PointT &p) { return std::isfinite(p.x) && std::isfinite(p.y); };
  if (!indices) return std::any_of(cloud.begin(), cloud.end(), finite);
  return std::any_of(indices->begin(), indices->end(), [&](pcl::index_t k) { return finite(cloud[k]); });
}

}  // namespace detail

template <typename PointSource, typename PointTarget, typename Scalar>
ContourRegistration<PointSource, PointTarget, Scalar>::ContourRegistration() {
  reg_name_ = "ContourRegistration";
  this->tree_.reset(new LazyKdTree<PointTarget>());
  writePclSettings(params_);
}

template <typename PointSource, typename PointTarget, typename Scalar>
void ContourRegistration<PointSource, PointTarget, Scalar>::writePclSettings(const RegistrationParams &params) {
  this->ransac_iterations_ = params.ransac.max_iterations;
  this->inlier_threshold_ = params.ransac.inlier_threshold;
  this->max_iterations_ = params.refinement.max_iterations;
  this->corr_dist_threshold_ = params.refinement.max_distance;
  this->transformation_epsilon_ = params.refinement.stop_translation * params.refinement.stop_translation;
  this->transformation_rotation_epsilon_ = std::cos(params.refinement.stop_rotation);
}

template <typename PointSource, typename PointTarget, typename Scalar>
void ContourRegistration<PointSource, PointTarget, Scalar>::setRegistrationParams(const RegistrationParams &params) {
  params_ = params;
  writePclSettings(params);
}

template <typename PointSource, typename PointTarget, typename Scalar>
RegistrationParams ContourRegistration<PointSource, PointTarget, Scalar>::getRegistrationParams() const {
  RegistrationParams params = params_;
  params.ransac.max_iterations = this->ransac_iterations_;
  params.ransac.inlier_threshold = this->inlier_threshold_;
  params.refinement.max_iterations = this->max_iterations_;
  params.refinement.max_distance = this->corr_dist_threshold_;
  params.refinement.min_distance = std::min(params.refinement.min_distance, params.refinement.max_distance);
  params.refinement.stop_translation = std::sqrt(std::max(0.0, this->transformation_epsilon_));
  params.refinement.stop_rotation = std::acos(std::clamp(this->transformation_rotation_epsilon_, -1.0, 1.0));
  return params;
}

template <typename PointSource, typename PointTarget, typename Scalar>
void ContourRegistration<PointSource, PointTarget, Scalar>::holdSource(const PointCloudSourceConstPtr &cloud) {
  // pcl::Registration would keep the previous source on an empty one (and dereference a null
  // one); align() must fail on this one instead.
  if (cloud && !cloud->empty())
    Base::setInputSource(cloud);
  else
    input_ = cloud;
}

template <typename PointSource, typename PointTarget, typename Scalar>
void ContourRegistration<PointSource, PointTarget, Scalar>::holdTarget(const PointCloudTargetConstPtr &cloud) {
  if (cloud && !cloud->empty()) {
    Base::setInputTarget(cloud);
  } else {
    target_ = cloud;
    this->target_cloud_updated_ = true;
  }
}

template <typename PointSource, typename PointTarget, typename Scalar>
void ContourRegistration<PointSource, PointTarget, Scalar>::setInputSource(const PointCloudSourceConstPtr &cloud) {
  if (cloud && cloud->empty())
    PCL_ERROR("[contour_reg::%s::setInputSource] Empty source cloud.\n", getClassName().c_str());
  holdSource(cloud);
  source_extracted_ = reuse_source_ = false;
}

template <typename PointSource, typename PointTarget, typename Scalar>
void ContourRegistration<PointSource, PointTarget, Scalar>::setInputTarget(const PointCloudTargetConstPtr &cloud) {
  if (cloud && cloud->empty())
    PCL_ERROR("[contour_reg::%s::setInputTarget] Empty target cloud.\n", getClassName().c_str());
  holdTarget(cloud);
  target_extracted_ = false;
}

template <typename PointSource, typename PointTarget, typename Scalar>
void ContourRegistration<PointSource, PointTarget, Scalar>::swapSourceAndTarget() {
  static_assert(std::is_same_v<PointSource, PointTarget>, "swapSourceAndTarget needs one point type");
  const PointCloudSourceConstPtr source = input_;
  holdSource(target_);
  holdTarget(source);
  std::swap(source_features_, target_features_);
  std::swap(source_order_, target_order_);
  std::swap(source_sweep_, target_sweep_);
  std::swap(source_extracted_, target_extracted_);
  // The target is the whole cloud: features of the points some indices named are not its.
  if (source_indexed_) target_extracted_ = false;
  source_indexed_ = false;
  reuse_source_ = source_extracted_;
}

template <typename PointSource, typename PointTarget, typename Scalar>
void ContourRegistration<PointSource, PointTarget, Scalar>::clearSource() {
  input_.reset();
  source_features_.clear();
  source_extracted_ = reuse_source_ = false;
  converged_ = false;  // pcl::Registration::align() returns early without a source and leaves it
}

template <typename PointSource, typename PointTarget, typename Scalar>
void ContourRegistration<PointSource, PointTarget, Scalar>::clearTarget() {
  target_.reset();
  this->target_cloud_updated_ = true;
  target_features_.clear();
  target_extracted_ = false;
  converged_ = false;
}

template <typename PointSource, typename PointTarget, typename Scalar>
void ContourRegistration<PointSource, PointTarget, Scalar>::setSourceSweep(const Sweep &sweep) {
  source_sweep_ = sweep;
  source_extracted_ = reuse_source_ = false;
}

template <typename PointSource, typename PointTarget, typename Scalar>
void ContourRegistration<PointSource, PointTarget, Scalar>::setTargetSweep(const Sweep &sweep) {
  target_sweep_ = sweep;
  target_extracted_ = false;
}

template <typename PointSource, typename PointTarget, typename Scalar>
void ContourRegistration<PointSource, PointTarget, Scalar>::setContourParams(const ContourParams &params) {
  contour_params_ = params;
  source_extracted_ = target_extracted_ = reuse_source_ = false;
}

template <typename PointSource, typename PointTarget, typename Scalar>
void ContourRegistration<PointSource, PointTarget, Scalar>::computeTransformation(PointCloudSource &output,
                                                                                  const Matrix4 &guess) {
  const Matrix4 fallback = guess;
  final_transformation_ = transformation_ = fallback;
  converged_ = false;
  nr_iterations_ = 0;
  const RegistrationParams params = getRegistrationParams();
  std::string why;
  if (!contour_params_.validate(&why) || !params.validate(&why)) {
    result_ = RegistrationResult{};
    PCL_ERROR("[contour_reg::%s::computeTransformation] Invalid parameters: %s.\n", getClassName().c_str(),
              why.c_str());
    result_.status = RegistrationStatus::kInvalidParameters;
    result_.reason = why;
    return;
  }
  // The source points setIndices() names, as PCL's ICP takes them (none set: the whole cloud).
  const pcl::Indices *indices = this->fake_indices_ ? nullptr : this->indices_.get();
  if (indices && !indicesWithin(*input_, *indices)) {
    result_ = RegistrationResult{};
    result_.reason =
        "an index of setIndices() names no point of the " + std::to_string(input_->size()) + "-point source cloud";
    PCL_ERROR("[contour_reg::%s::computeTransformation] %s.\n", getClassName().c_str(), result_.reason.c_str());
    result_.status = RegistrationStatus::kInvalidParameters;
    return;
  }
  if (!detail::hasFinitePoint(*input_, indices) || !detail::hasFinitePoint(*target_)) {
    result_ = RegistrationResult{};
    result_.reason = !detail::hasFinitePoint(*input_, indices) ? "source cloud has no valid point"
                                                               : "target cloud has no valid point";
    PCL_ERROR("[contour_reg::%s::computeTransformation] %s.\n", getClassName().c_str(), result_.reason.c_str());
    result_.status = RegistrationStatus::kTooFewSpecialPoints;
    return;
  }
  // Features swapped in from the target are of the whole cloud: with indices they are not the source's.
  // The bearing order of the polar code is kept only for a visualisation callback (showCornerPairs).
  const bool keep_order = static_cast<bool>(this->update_visualizer_);
  if (!reuse_source_ || indices) {
    source_order_.clear();
    extractContourFeatures(*input_, contour_params_, source_features_, indices, keep_order ? &source_order_ : nullptr,
                           source_sweep_);
  }
  reuse_source_ = false;  // the next align() reads the source again
  source_extracted_ = true;
  source_indexed_ = indices != nullptr;
  if (!target_extracted_) {
    target_order_.clear();
    extractContourFeatures(*target_, contour_params_, target_features_, nullptr, keep_order ? &target_order_ : nullptr,
                           target_sweep_);
    target_extracted_ = true;
  }

  // The planar part of the guess, source to target.
  Eigen::Matrix3d guess2d = Eigen::Matrix3d::Identity();
  guess2d.topLeftCorner<2, 2>() = guess.template topLeftCorner<2, 2>().template cast<double>();
  guess2d.topRightCorner<2, 1>() = guess.template block<2, 1>(0, 3).template cast<double>();
  guess2d = rigidPart(guess2d);

  rng_.seed(seed_);
  registerContours(source_features_, target_features_, params, rng_, &guess2d, buffers_, result_);
  nr_iterations_ = result_.ransac_iterations;
  converged_ = result_.converged;
  if (!converged_) {
    PCL_DEBUG("[contour_reg::%s::computeTransformation] Not converged: %s.\n", getClassName().c_str(),
              result_.reason.c_str());
    pcl::transformPointCloud(output, output, final_transformation_);
    showCornerPairs(output, indices);
    return;
  }
  Matrix4 transform = Matrix4::Identity();
  transform.template topLeftCorner<2, 2>() = result_.transform.topLeftCorner<2, 2>().template cast<Scalar>();
  transform.template block<2, 1>(0, 3) = result_.transform.topRightCorner<2, 1>().template cast<Scalar>();
  final_transformation_ = transformation_ = transform;
  pcl::transformPointCloud(output, output, final_transformation_);
  showCornerPairs(output, indices);
}

template <typename PointSource, typename PointTarget, typename Scalar>
void ContourRegistration<PointSource, PointTarget, Scalar>::showCornerPairs(const PointCloudSource &output,
                                                                            const pcl::Indices *indices) const {
  if (!this->update_visualizer_) return;
  // The cloud point at a special point's vertex: its beam in the polar code, that beam's
  // position in the cloud (or in the indices) before any sort by bearing.
  const auto pointOf = [](const ContourFeatures &features, const std::vector<int> &order, int special) {
    const int beam = nearestBeam(features, features.special_points[static_cast<std::size_t>(special)]);
    return beam >= 0 && static_cast<std::size_t>(beam) < order.size() ? order[static_cast<std::size_t>(beam)] : -1;
  };
  pcl::Indices sources, targets;
  if (converged_ && !result_.from_local_fallback) {
    for (const int inlier : result_.inliers) {
      const Correspondence &pair = result_.candidates[static_cast<std::size_t>(inlier)];
      const int source = pointOf(source_features_, source_order_, pair.source);
      const int target = pointOf(target_features_, target_order_, pair.target);
      if (source < 0 || target < 0) continue;
      sources.push_back(indices ? (*indices)[static_cast<std::size_t>(source)] : source);
      targets.push_back(target);
    }
  }
  this->update_visualizer_(output, sources, *target_, targets);
}

}  // namespace contour_reg
