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
/// z ignored); a target may also be several scans moved into one frame and appended, as
/// pcl::registration::MetaRegistration keeps its map. As in PCL, every setInputSource() /
/// setInputTarget() is new data, also when it passes the same pointer again: a cloud
/// refilled in place must be set again, and then its new contents count. align() reads the
/// source cloud it holds every time (as ICP does); the target's special points are extracted
/// at the first align() after setInputTarget() and kept for later align() calls until the
/// target is set again (as PCL keeps the target's kd-tree). swapSourceAndTarget() is the one
/// path that reuses the source's special points: odometry (each scan against the previous
/// one) swaps, sets the new scan as source, and aligns, so each scan is read once.
/// setIndices() names the source points to register, in beam order,
/// as ContourCornerEstimation takes them (the target is the whole cloud, as in pcl::Registration).
/// They must name points of the source: PCL's align() copies those points to its output before
/// the registration runs (which then reports an index outside as kInvalidParameters).
///
/// PCL's settings: setRANSACIterations() is the RANSAC iterations k,
/// setRANSACOutlierRejectionThreshold() the RANSAC inlier threshold t on corner vertices (m),
/// setMaximumIterations() the refinement's Gauss-Newton iterations,
/// setMaxCorrespondenceDistance() the refinement's widest pairing distance (m; it shrinks each
/// iteration to refinement.min_distance, or stays at this distance when that is smaller), and
/// setTransformationEpsilon() / setTransformationRotationEpsilon() its stop: a step shorter
/// than sqrt(epsilon) metres that turns by less than acos(rotation epsilon). They and
/// setRegistrationParams() write the same settings: whichever is called last holds.
/// setEuclideanFitnessEpsilon() and PCL's convergence criteria have no effect (RANSAC and the
/// judgement of the result decide convergence). getFinalTransformation() is the answer,
/// getFitnessScore() PCL's score of it over the finite source points (a NaN beam has no
/// nearest target point: lazy_kdtree.h); nr_iterations_ counts the RANSAC iterations. A
/// callback of registerVisualizationCallback() (pcl::RegistrationVisualizer's) is called once
/// per align() with the moved source and the corner pairs that decided a converged motion, the
/// cloud points at their vertices (none where the contours decided it, or nothing converged).
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
/// Failure: hasConverged() is false, getResult().status names the verdict (too few special
/// points, low overlap, unconstrained, ambiguous, contradicted, ...; see RegistrationStatus) and
/// getFailureReason() says it in words; the final transformation is the guess. An empty or
/// all-NaN cloud is reported with PCL_ERROR. isDegenerate() flags converged estimates left
/// unconstrained in some direction (a corridor or a single wall with fewer than three inlier
/// corners); contour_reg's odometry treats them as failures. getCovariance() gives the 3x3
/// covariance of x, y, yaw (docs/reliability.md: its calibration on simulated and real scans).
template <typename PointSource, typename PointTarget, typename Scalar = float>
class ContourRegistration : public pcl::Registration<PointSource, PointTarget, Scalar> {
 public:
  using Base = pcl::Registration<PointSource, PointTarget, Scalar>;
  using Ptr = std::shared_ptr<ContourRegistration<PointSource, PointTarget, Scalar>>;
  using ConstPtr = std::shared_ptr<const ContourRegistration<PointSource, PointTarget, Scalar>>;
  using Base::converged_;
  using Base::final_transformation_;
  using Base::getClassName;
  using Base::input_;
  using Base::nr_iterations_;
  using Base::reg_name_;
  using Base::target_;
  using Base::transformation_;
  using typename Base::Matrix4;
  using typename Base::PointCloudSource;
  using typename Base::PointCloudSourceConstPtr;
  using typename Base::PointCloudTargetConstPtr;

  ContourRegistration();

  /// New data: read at every align().
  void setInputSource(const PointCloudSourceConstPtr &cloud) override;
  /// New data: its special points are extracted at the next align() and kept until it is set again.
  void setInputTarget(const PointCloudTargetConstPtr &cloud) override;
  /// Makes the source the target and the target the source, each with the special points
  /// extracted from it at the last align(). For clouds not changed since that align(): the
  /// odometry step is swapSourceAndTarget(), setInputSource(next scan), align().
  void swapSourceAndTarget();
  /// Forgets the source (or the target) and what was extracted from it; align() then fails
  /// until a new one is set.
  void clearSource();
  void clearTarget();

  /// Scans taken while moving (deskew.h): the source's (target's) points, in cloud order, were
  /// taken sweep.time_increment s apart while the sensor moved by sweep.motion (its velocity
  /// in its own frame, constant or changing during the sweep, e.g. from wheel odometry). align()
  /// deskews them into the frame of the sensor at the first point before extracting special
  /// points, so the transform is between those frames. The default Sweep: taken at once.
  /// Kept until set again; setting one counts as new data.
  void setSourceSweep(const Sweep &sweep);
  void setTargetSweep(const Sweep &sweep);
  const Sweep &getSourceSweep() const { return source_sweep_; }
  const Sweep &getTargetSweep() const { return target_sweep_; }

  /// Stages A-C settings (contour, equalization, corner filter, special points).
  void setContourParams(const ContourParams &params);
  const ContourParams &getContourParams() const { return contour_params_; }
  /// Stages D-F and refinement settings (also PCL's iteration, threshold and epsilon settings).
  void setRegistrationParams(const RegistrationParams &params);
  /// The settings align() uses, with those set through PCL's setters.
  RegistrationParams getRegistrationParams() const;

  void setTransformModel(TransformModel model) { params_.ransac.model = model; }
  void setFragmentDistance(FragmentDistance form) { params_.correspondence.distance = form; }
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
  /// Stages A-C of the source and of the target as the last align() used them.
  const ContourFeatures &getSourceFeatures() const { return source_features_; }
  const ContourFeatures &getTargetFeatures() const { return target_features_; }

 protected:
  void computeTransformation(PointCloudSource &output, const Matrix4 &guess) override;

 private:
  ContourParams contour_params_;
  RegistrationParams params_;
  unsigned seed_ = 42;
  std::mt19937 rng_;
  // Base-class members that PCL's setters write, from params_ (setRegistrationParams).
  void writePclSettings(const RegistrationParams &params);
  // A source or target without the feature bookkeeping of the public setters.
  void holdSource(const PointCloudSourceConstPtr &cloud);
  void holdTarget(const PointCloudTargetConstPtr &cloud);
  // PCL's visualisation callback, once per align(): the moved source and the corner pairs that
  // decided a converged motion (none for one the contours decided, or none converged).
  void showCornerPairs(const PointCloudSource &output, const pcl::Indices *indices) const;

  Sweep source_sweep_, target_sweep_;
  ContourFeatures source_features_, target_features_;
  RegistrationBuffers buffers_;  // the target's refinement index, rebuilt for a new target extraction
  // Whether the features were extracted from the cloud now set (at the last align()): the
  // target's are used while true; the source's only right after swapSourceAndTarget().
  bool source_extracted_ = false, target_extracted_ = false;
  bool reuse_source_ = false;
  bool source_indexed_ = false;  // the source's features are of the points setIndices() named
  // The position in the cloud (or in the indices) of each point of the polar code the
  // features were extracted from, as polarCodeFromCloud() sorts them: for showCornerPairs().
  std::vector<int> source_order_, target_order_;
  RegistrationResult result_;
};

}  // namespace contour_reg

#include "contour_reg/impl/contour_registration.hpp"

namespace contour_reg {
extern template class ContourRegistration<pcl::PointXYZ, pcl::PointXYZ>;
extern template class ContourRegistration<pcl::PointXYZI, pcl::PointXYZI>;
}  // namespace contour_reg
