#pragma once
/// @file contour_registration.h
/// The contour method as a pcl::Registration: stands wherever ICP or NDT stands.

#include <random>
#include <string>

#include <pcl/registration/registration.h>

#include "contour_reg/cloud_conversions.h"
#include "contour_reg/core/contour_features.h"
#include "contour_reg/core/registration.h"

namespace contour_reg {

/// Registers two 2-D LIDAR scans by contour analysis: corner special points of each scan
/// (paper eqs. 1-13), pairs by local-fragment distance (eq. 14), a rigid (or the paper's
/// affine, eqs. 15-17) transform inside RANSAC, then a point-to-line refinement on the
/// contours. getFinalTransformation() maps the source into the target frame (PCL's
/// convention); z is left alone.
///
/// Input: scans as ContourCornerEstimation takes them (beam order, NaN for invalid beams,
/// z ignored). The target's special points are cached while the target is unchanged,
/// and when the new target is the previous source cloud (odometry: each scan against the
/// previous one) its features are reused.
///
/// The initial guess of align(output, guess): the corner match needs none (the fragment
/// distance is rotation invariant). The guess is refined on the contours where the corners
/// alone cannot decide: it is the first start of the local fallback, a motion of at most
/// five corners must agree with its refinement or fit clearly better, and of two motions
/// that fit equally well the one nearer the guess wins. It is the answer reported when
/// registration fails. With setGuessGate(d > 0), pairs whose target lies more than
/// d metres from the guessed position of their source point (or whose rotation disagrees
/// with the guess) are dropped. With the paper's rotation-dependent fragment distance
/// (FragmentDistance::kReal), the source fragments are first turned by the guess's yaw.
///
/// Failure: hasConverged() is false and getFailureReason() says why (too few special
/// points, too few inliers, degenerate geometry); the final transformation is the guess.
/// An empty or all-NaN cloud is reported with PCL_ERROR. isDegenerate() flags converged
/// estimates left unconstrained in some direction (a corridor or a single wall with fewer
/// than three inlier corners); contour_reg's odometry treats them as failures.
/// getCovariance() gives the 3x3 covariance of x, y, yaw (calibrated: mean NEES about 3).
template <typename PointSource, typename PointTarget, typename Scalar = float>
class ContourRegistration : public pcl::Registration<PointSource, PointTarget, Scalar> {
 public:
  using Base = pcl::Registration<PointSource, PointTarget, Scalar>;
  using Ptr = std::shared_ptr<ContourRegistration<PointSource, PointTarget, Scalar>>;
  using ConstPtr = std::shared_ptr<const ContourRegistration<PointSource, PointTarget, Scalar>>;
  using typename Base::Matrix4;
  using typename Base::PointCloudSource;
  using typename Base::PointCloudSourceConstPtr;
  using typename Base::PointCloudTargetConstPtr;
  using Base::converged_;
  using Base::final_transformation_;
  using Base::getClassName;
  using Base::input_;
  using Base::nr_iterations_;
  using Base::reg_name_;
  using Base::target_;
  using Base::transformation_;

  ContourRegistration();

  void setInputSource(const PointCloudSourceConstPtr &cloud) override;
  void setInputTarget(const PointCloudTargetConstPtr &cloud) override;

  /// Stages A-C settings (contour, equalization, corner filter, special points).
  void setContourParams(const ContourParams &params);
  const ContourParams &getContourParams() const { return contour_params_; }
  /// Stages D-F and refinement settings.
  void setRegistrationParams(const RegistrationParams &params) { params_ = params; }
  const RegistrationParams &getRegistrationParams() const { return params_; }

  void setTransformModel(TransformModel model) { params_.ransac.model = model; }
  void setFragmentDistance(FragmentDistance form) { params_.correspondence.distance = form; }
  /// t: RANSAC inlier threshold on corner vertices, m.
  void setInlierThreshold(double metres) { params_.ransac.inlier_threshold = metres; }
  /// k: RANSAC iterations.
  void setRansacIterations(int iterations) { params_.ransac.max_iterations = iterations; }
  /// Enables the point-to-line refinement on the contours (on by default).
  void setRefinement(bool enabled) { params_.refinement.enabled = enabled; }
  /// Gate pairs by the initial guess (m); 0 ignores the guess for pairing.
  void setGuessGate(double metres) { params_.guess_max_distance = metres; }
  /// Seed of the object's own random generator (RANSAC); re-seeded before every align().
  void setSeed(unsigned seed) { seed_ = seed; }

  /// Everything about the last align(): pairs, inliers, errors, covariance.
  const RegistrationResult &getResult() const { return result_; }
  /// Why the last align() did not converge; empty when it did.
  const std::string &getFailureReason() const { return result_.reason; }
  bool isDegenerate() const { return result_.degenerate; }
  const Eigen::Matrix3d &getCovariance() const { return result_.covariance; }
  const ContourFeatures &getSourceFeatures() const { return source_features_; }
  const ContourFeatures &getTargetFeatures() const { return target_features_; }

 protected:
  void computeTransformation(PointCloudSource &output, const Matrix4 &guess) override;

 private:
  ContourParams contour_params_;
  RegistrationParams params_;
  unsigned seed_ = 42;
  std::mt19937 rng_;
  ContourFeatures source_features_, target_features_;
  RegistrationBuffers buffers_;  // the target's refinement index, kept while the target is unchanged
  bool source_ready_ = false, target_ready_ = false;
  const void *source_cloud_ = nullptr;  // identity of the cloud source_features_ belong to
  RegistrationResult result_;
};

}  // namespace contour_reg

#include "contour_reg/impl/contour_registration.hpp"

namespace contour_reg {
extern template class ContourRegistration<pcl::PointXYZ, pcl::PointXYZ>;
extern template class ContourRegistration<pcl::PointXYZI, pcl::PointXYZI>;
}  // namespace contour_reg
