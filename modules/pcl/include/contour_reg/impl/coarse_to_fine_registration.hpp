#pragma once

#include <cmath>
#include <type_traits>

#include <pcl/common/transforms.h>
#include <pcl/filters/filter.h>

#include "contour_reg/coarse_to_fine_registration.h"
#include "contour_reg/lazy_kdtree.h"

namespace contour_reg {

namespace detail {

// The cloud without its NaN points: the cloud itself when it is dense, else a copy into
// `buffer`. With `indices`, the finite points they name, copied (none when one names no point).
template <typename PointT>
typename pcl::PointCloud<PointT>::ConstPtr finitePoints(const typename pcl::PointCloud<PointT>::ConstPtr &cloud,
                                                        typename pcl::PointCloud<PointT>::Ptr &buffer,
                                                        const pcl::Indices *indices = nullptr) {
  if (!cloud || (cloud->is_dense && !indices)) return cloud;
  if (!buffer) buffer = pcl::make_shared<pcl::PointCloud<PointT>>();
  if (!indices) {
    pcl::Indices kept;
    pcl::removeNaNFromPointCloud(*cloud, *buffer, kept);
    return buffer;
  }
  buffer->clear();
  if (indicesWithin(*cloud, *indices))
    for (const pcl::index_t k : *indices)
      if (pcl::isXYZFinite((*cloud)[k])) buffer->push_back((*cloud)[k]);
  buffer->is_dense = true;
  return buffer;
}

}  // namespace detail

template <typename PointSource, typename PointTarget, typename Scalar>
CoarseToFineRegistration<PointSource, PointTarget, Scalar>::CoarseToFineRegistration() {
  this->reg_name_ = "CoarseToFineRegistration";
  this->tree_.reset(new LazyKdTree<PointTarget>());  // getFitnessScore()'s: built when it searches
  coarse_ = pcl::make_shared<Coarse>();
  auto icp = pcl::make_shared<pcl::IterativeClosestPoint<PointSource, PointTarget, Scalar>>();
  icp->setTransformationEstimation(
      pcl::make_shared<pcl::registration::TransformationEstimation2D<PointSource, PointTarget, Scalar>>());
  icp->setMaxCorrespondenceDistance(0.3);
  icp->setMaximumIterations(30);
  icp->setTransformationEpsilon(1e-8);
  fine_ = icp;
}

template <typename PointSource, typename PointTarget, typename Scalar>
void CoarseToFineRegistration<PointSource, PointTarget, Scalar>::setInputSource(const PointCloudSourceConstPtr &cloud) {
  if (cloud && !cloud->empty())
    Base::setInputSource(cloud);
  else
    input_ = cloud;
  coarse_->setInputSource(cloud);
}

template <typename PointSource, typename PointTarget, typename Scalar>
void CoarseToFineRegistration<PointSource, PointTarget, Scalar>::setInputTarget(const PointCloudTargetConstPtr &cloud) {
  if (cloud && !cloud->empty()) {
    Base::setInputTarget(cloud);
  } else {
    target_ = cloud;
    this->target_cloud_updated_ = true;
  }
  coarse_->setInputTarget(cloud);
  finite_target_ready_ = false;
}

template <typename PointSource, typename PointTarget, typename Scalar>
void CoarseToFineRegistration<PointSource, PointTarget, Scalar>::swapSourceAndTarget() {
  static_assert(std::is_same_v<PointSource, PointTarget>, "swapSourceAndTarget needs one point type");
  const PointCloudSourceConstPtr source = input_;
  input_ = target_;
  target_ = source;
  this->source_cloud_updated_ = this->target_cloud_updated_ = true;
  coarse_->swapSourceAndTarget();
  // The source's finite points of the last align() serve the new target; the new source's are
  // made at the next align() anyway.
  std::swap(finite_source_, finite_target_);
  std::swap(source_buffer_, target_buffer_);
  // Those of the points some indices named are not the whole target's.
  finite_target_ready_ = static_cast<bool>(finite_target_) && !finite_source_indexed_;
  finite_source_indexed_ = false;
}

template <typename PointSource, typename PointTarget, typename Scalar>
void CoarseToFineRegistration<PointSource, PointTarget, Scalar>::clearSource() {
  input_.reset();
  coarse_->clearSource();
  finite_source_.reset();
  converged_ = false;  // pcl::Registration::align() returns early without a source and leaves it
}

template <typename PointSource, typename PointTarget, typename Scalar>
void CoarseToFineRegistration<PointSource, PointTarget, Scalar>::clearTarget() {
  target_.reset();
  this->target_cloud_updated_ = true;
  coarse_->clearTarget();
  finite_target_.reset();
  finite_target_ready_ = false;
  converged_ = false;
}

template <typename PointSource, typename PointTarget, typename Scalar>
void CoarseToFineRegistration<PointSource, PointTarget, Scalar>::computeTransformation(PointCloudSource &output,
                                                                                       const Matrix4 &guess) {
  final_transformation_ = transformation_ = guess;
  converged_ = false;
  fine_rejected_ = false;
  fine_from_guess_ = false;
  PointCloudSource scratch;
  // The source points setIndices() names (none set: the whole cloud), for both stages.
  const pcl::Indices *indices = this->fake_indices_ ? nullptr : this->indices_.get();
  coarse_->setIndices(indices ? this->indices_ : pcl::IndicesPtr());
  coarse_->align(scratch, guess);

  // The fine stage reads the source every time and the target once per setInputTarget().
  finite_source_ = detail::finitePoints<PointSource>(input_, source_buffer_, indices);
  finite_source_indexed_ = indices != nullptr;
  if (!finite_target_ready_) {
    finite_target_ = detail::finitePoints<PointTarget>(target_, target_buffer_);
    finite_target_ready_ = true;
  }
  const bool fine_possible = finite_source_ && finite_target_ && !finite_source_->empty() && !finite_target_->empty();

  if (!coarse_->hasConverged()) {
    if (fine_from_guess_enabled_ && isUndecided(coarse_->getResult().status) && fine_possible && isLocalGuess(guess)) {
      fine_->setInputSource(finite_source_);
      fine_->setInputTarget(finite_target_);
      fine_->align(scratch, guess);
      fine_from_guess_ = true;
      converged_ = fine_->hasConverged();
      if (converged_) final_transformation_ = transformation_ = fine_->getFinalTransformation();
    }
    pcl::transformPointCloud(*input_, output, final_transformation_);
    return;
  }
  const Matrix4 coarse = coarse_->getFinalTransformation();
  final_transformation_ = transformation_ = coarse;
  converged_ = true;
  if (!fine_possible) {
    fine_rejected_ = true;
    pcl::transformPointCloud(*input_, output, final_transformation_);
    return;
  }
  fine_->setInputSource(finite_source_);
  fine_->setInputTarget(finite_target_);
  fine_->align(scratch, coarse);
  const Matrix4 fine = fine_->getFinalTransformation();
  const Matrix4 change = coarse.inverse() * fine;
  const double moved = std::hypot(double(change(0, 3)), double(change(1, 3)));
  const double turned = std::abs(std::atan2(double(change(1, 0)), double(change(0, 0))));
  fine_rejected_ = !fine_->hasConverged() || moved > max_fine_translation_ || turned > max_fine_rotation_;
  if (!fine_rejected_) final_transformation_ = transformation_ = fine;
  pcl::transformPointCloud(*input_, output, final_transformation_);
}

}  // namespace contour_reg
