#pragma once
/// @file coarse_to_fine_registration.h
/// Two registrations in a row: a global coarse stage (the contour method by default) whose
/// answer is the initial guess of a local fine stage (PCL ICP with TransformationEstimation2D).

#include <memory>

#include <pcl/registration/icp.h>
#include <pcl/registration/registration.h>
#include <pcl/registration/transformation_estimation_2D.h>

#include "contour_reg/contour_registration.h"

namespace contour_reg {

/// m: PCL's local methods (ICP, NDT, GICP) register in single precision, which resolves points
/// 10 km from the origin to a millimetre and no finer; a guess that moves the source further
/// leaves them nothing to match, and from 1e38 m (or a NaN) their kd-tree search meets
/// coordinates that are not finite, which it refuses with an assertion.
constexpr double kFarthestLocalGuess = 1e4;

/// True when a PCL local method can start from `guess` (any matrix whose top-right column
/// holds the translation: 3 x 3 planar or 4 x 4): finite, moving at most kFarthestLocalGuess.
template <typename Matrix>
bool isLocalGuess(const Matrix &guess) {
  const auto translation = guess.template topRightCorner<2, 1>();
  return guess.allFinite() && double(translation.norm()) <= kFarthestLocalGuess;
}

/// Coarse-to-fine registration as one pcl::Registration.
///
/// align(output, guess) runs the coarse stage, a ContourRegistration, from `guess`; when it
/// converges, the fine stage starts from its answer on the same clouds without their NaN
/// points. The result has converged only when both stages did and the fine stage moved the
/// coarse answer by at most setMaxFineCorrection() (metres, radians): a larger correction
/// means ICP fell into another minimum, and the coarse answer is kept (converged, flagged by
/// fineStageRejected()). When the coarse stage's scans do not decide the motion
/// (isUndecided(): too few special points or inliers, low overlap, unconstrained, ambiguous, contradicted)
/// and setFineFromGuess(true) (the default), the fine stage runs from the guess alone and its
/// own convergence is reported (fineFromGuess() tells); a local answer, right only when the
/// guess was close. A guess the fine stage cannot start from (isLocalGuess() false) is not
/// tried: the coarse stage's verdict stands. Invalid parameters end there: not converged,
/// final transformation = guess.
///
/// Inputs follow ContourRegistration's contract: every setInputSource()/setInputTarget() is
/// new data, align() reads the source it holds every time, and swapSourceAndTarget() is the
/// odometry step that reuses what was extracted from the last source. setIndices() names the
/// source points both stages register. The stages are configured through getCoarseStage()
/// and getFineStage(); this class's own PCL setters (setMaximumIterations(),
/// setMaxCorrespondenceDistance(), ...) have no effect.
///
/// Defaults: ContourRegistration, then ICP with TransformationEstimation2D, 0.3 m
/// correspondence distance, 30 iterations, 1e-8 transformation epsilon.
template <typename PointSource, typename PointTarget, typename Scalar = float>
class CoarseToFineRegistration : public pcl::Registration<PointSource, PointTarget, Scalar> {
 public:
  using Base = pcl::Registration<PointSource, PointTarget, Scalar>;
  using Ptr = std::shared_ptr<CoarseToFineRegistration<PointSource, PointTarget, Scalar>>;
  using ConstPtr = std::shared_ptr<const CoarseToFineRegistration<PointSource, PointTarget, Scalar>>;
  using Coarse = ContourRegistration<PointSource, PointTarget, Scalar>;
  using Fine = pcl::Registration<PointSource, PointTarget, Scalar>;
  using Base::converged_;
  using Base::final_transformation_;
  using Base::input_;
  using Base::target_;
  using Base::transformation_;
  using typename Base::Matrix4;
  using typename Base::PointCloudSource;
  using typename Base::PointCloudSourceConstPtr;
  using typename Base::PointCloudTarget;
  using typename Base::PointCloudTargetConstPtr;

  CoarseToFineRegistration();

  void setCoarseStage(const typename Coarse::Ptr &stage) { coarse_ = stage; }
  void setFineStage(const typename Fine::Ptr &stage) { fine_ = stage; }
  const typename Coarse::Ptr &getCoarseStage() const { return coarse_; }
  const typename Fine::Ptr &getFineStage() const { return fine_; }
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

  /// New data: read at every align().
  void setInputSource(const PointCloudSourceConstPtr &cloud) override;
  /// New data: its features and finite points are prepared at the next align() and kept until it is set again.
  void setInputTarget(const PointCloudTargetConstPtr &cloud) override;
  /// As ContourRegistration::swapSourceAndTarget(): the odometry step for clouds not changed since the last align().
  void swapSourceAndTarget();
  void clearSource();
  void clearTarget();

 protected:
  void computeTransformation(PointCloudSource &output, const Matrix4 &guess) override;

 private:
  typename Coarse::Ptr coarse_;
  typename Fine::Ptr fine_;
  // The clouds without their NaN points, as the fine stage takes them; the target's is made
  // at the first align() after setInputTarget(), the source's at every align().
  PointCloudSourceConstPtr finite_source_;
  PointCloudTargetConstPtr finite_target_;
  typename PointCloudSource::Ptr source_buffer_;  // NaN-free copies of clouds that are not dense
  typename PointCloudTarget::Ptr target_buffer_;
  bool finite_target_ready_ = false;
  bool finite_source_indexed_ = false;  // finite_source_ holds the points setIndices() named
  double max_fine_translation_ = 0.10, max_fine_rotation_ = 0.035;
  bool fine_rejected_ = false;
  bool fine_from_guess_enabled_ = true, fine_from_guess_ = false;
};

}  // namespace contour_reg

#include "contour_reg/impl/coarse_to_fine_registration.hpp"

namespace contour_reg {
extern template class CoarseToFineRegistration<pcl::PointXYZ, pcl::PointXYZ>;
extern template class CoarseToFineRegistration<pcl::PointXYZI, pcl::PointXYZI>;
}  // namespace contour_reg
