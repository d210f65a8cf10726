#pragma once
/// @file coarse_to_fine_registration.h
/// Two registrations in a row: a global coarse stage (the contour method by default) whose
/// answer is the initial guess of a local fine stage (PCL ICP with TransformationEstimation2D).

#include <memory>

#include <pcl/filters/filter.h>
#include <pcl/registration/icp.h>
#include <pcl/registration/registration.h>
#include <pcl/registration/transformation_estimation_2D.h>

#include "contour_reg/contour_registration.h"

namespace contour_reg {

/// Coarse-to-fine registration as one pcl::Registration.
///
/// align(output, guess) runs the coarse stage from `guess`; when it converges, the fine
/// stage starts from its answer on the same clouds without their NaN points. The result
/// has converged only when both stages did and the fine stage moved the coarse answer by
/// at most setMaxFineCorrection() (metres, radians): a larger correction means ICP fell
/// into another minimum, and the coarse answer is kept (converged, flagged by
/// fineStageRejected()). When the coarse stage fails because its features cannot decide
/// (a ContourRegistration reporting too few special points, pairs or inliers) and
/// setFineFromGuess(true) (the default), the fine stage runs from the guess alone and its
/// own convergence is reported (fineFromGuess() tells); a local answer, right only when
/// the guess was close. Any other coarse failure (degenerate geometry, invalid input)
/// ends there: not converged, final transformation = guess.
///
/// Defaults: ContourRegistration, then ICP with TransformationEstimation2D, 0.3 m
/// correspondence distance, 30 iterations, 1e-8 transformation epsilon.
template <typename PointSource, typename PointTarget, typename Scalar = float>
class CoarseToFineRegistration : public pcl::Registration<PointSource, PointTarget, Scalar> {
 public:
  using Base = pcl::Registration<PointSource, PointTarget, Scalar>;
  using Ptr = std::shared_ptr<CoarseToFineRegistration<PointSource, PointTarget, Scalar>>;
  using Stage = pcl::Registration<PointSource, PointTarget, Scalar>;
  using typename Base::Matrix4;
  using typename Base::PointCloudSource;
  using typename Base::PointCloudSourceConstPtr;
  using typename Base::PointCloudTargetConstPtr;
  using Base::converged_;
  using Base::final_transformation_;
  using Base::input_;
  using Base::target_;
  using Base::transformation_;

  CoarseToFineRegistration() {
    this->reg_name_ = "CoarseToFineRegistration";
    coarse_ = std::make_shared<ContourRegistration<PointSource, PointTarget, Scalar>>();
    auto icp = std::make_shared<pcl::IterativeClosestPoint<PointSource, PointTarget, Scalar>>();
    icp->setTransformationEstimation(
        std::make_shared<pcl::registration::TransformationEstimation2D<PointSource, PointTarget, Scalar>>());
    icp->setMaxCorrespondenceDistance(0.3);
    icp->setMaximumIterations(30);
    icp->setTransformationEpsilon(1e-8);
    fine_ = icp;
  }

  void setCoarseStage(const typename Stage::Ptr &stage) { coarse_ = stage; }
  void setFineStage(const typename Stage::Ptr &stage) { fine_ = stage; }
  const typename Stage::Ptr &getCoarseStage() const { return coarse_; }
  const typename Stage::Ptr &getFineStage() const { return fine_; }
  /// Largest change the fine stage may make to the coarse answer (m, rad).
  void setMaxFineCorrection(double metres, double radians) {
    max_fine_translation_ = metres;
    max_fine_rotation_ = radians;
  }
  /// True when the last fine stage failed or moved too far and the coarse answer was kept.
  bool fineStageRejected() const { return fine_rejected_; }
  /// Run the fine stage from the guess when the coarse stage's features cannot decide.
  void setFineFromGuess(bool enabled) { fine_from_guess_enabled_ = enabled; }
  /// True when the last answer came from the fine stage alone, started at the guess.
  bool fineFromGuess() const { return fine_from_guess_; }

  void setInputSource(const PointCloudSourceConstPtr &cloud) override {
    if (cloud && !cloud->empty()) Base::setInputSource(cloud);
    else input_ = cloud;
    coarse_->setInputSource(cloud);
    finite_source_ = finite(cloud);
  }
  void setInputTarget(const PointCloudTargetConstPtr &cloud) override {
    if (cloud == target_ && finite_target_) return;
    if (cloud && !cloud->empty()) Base::setInputTarget(cloud);
    else target_ = cloud;
    coarse_->setInputTarget(cloud);
    if constexpr (std::is_same_v<PointSource, PointTarget>) {
      if (cloud && cloud == input_) {  // odometry: the last source becomes the target
        finite_target_ = finite_source_;
        return;
      }
    }
    finite_target_ = finite(cloud);
  }

 protected:
  void computeTransformation(PointCloudSource &output, const Matrix4 &guess) override {
    final_transformation_ = transformation_ = guess;
    converged_ = false;
    fine_rejected_ = false;
    fine_from_guess_ = false;
    PointCloudSource scratch;
    coarse_->align(scratch, guess);
    if (!coarse_->hasConverged()) {
      if (fine_from_guess_enabled_ && coarseUndecided() && finite_source_ && finite_target_ &&
          !finite_source_->empty() && !finite_target_->empty()) {
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

 private:
  bool coarseUndecided() const {
    const auto *contour = dynamic_cast<const ContourRegistration<PointSource, PointTarget, Scalar> *>(coarse_.get());
    if (!contour) return false;
    const RegistrationStatus status = contour->getResult().status;
    return status == RegistrationStatus::kTooFewSpecialPoints || status == RegistrationStatus::kTooFewCorrespondences ||
           status == RegistrationStatus::kTooFewInliers;
  }

  template <typename CloudPtr>
  static CloudPtr finite(const CloudPtr &cloud) {
    if (!cloud || cloud->is_dense) return cloud;
    using Cloud = typename std::remove_const_t<typename CloudPtr::element_type>;
    auto out = std::make_shared<Cloud>();
    pcl::Indices kept;
    pcl::removeNaNFromPointCloud(*cloud, *out, kept);
    return out;
  }

  typename Stage::Ptr coarse_, fine_;
  PointCloudSourceConstPtr finite_source_;
  PointCloudTargetConstPtr finite_target_;
  double max_fine_translation_ = 0.10, max_fine_rotation_ = 0.035;
  bool fine_rejected_ = false;
  bool fine_from_guess_enabled_ = true, fine_from_guess_ = false;
};

}  // namespace contour_reg
