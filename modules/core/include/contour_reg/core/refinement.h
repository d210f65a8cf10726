#pragma once
/// @file refinement.h
/// Beyond the paper: point-to-line refinement of a rigid estimate on the contours.
///
/// The corner vertices fix the transform to about a centimetre; the contours carry far
/// more evidence. Starting from the RANSAC estimate, equalized source vertices are paired
/// with the nearest equalized target vertex found by bearing (projective search, as in
/// PL-ICP; the vertices lie one step apart on the raw polyline however sparse the beams),
/// both equalized centred on their raw segments (equalizeCentred), so that the pairs do not
/// depend on which way the beams ran along a surface, and the point-to-line distances are
/// minimized by Gauss-Newton with Huber weights, the pairing distance shrinking each
/// iteration. The update moves the pose only along directions the contours constrain: where
/// the information matrix is degenerate (a corridor constrains nothing along its axis) the
/// corner estimate is kept. The step weighs each pair as the covariance counts it (samples
/// between the same two sparse raw returns share one sample's weight per sample_step) and
/// leaves out pairs with a vertex that ends a target contour (an occlusion edge: the source
/// may see past it). The information matrix also gives the covariance of the estimate, to
/// which a yaw term that grows with the turn is added (RefinementModel::turn_noise).

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "contour_reg/core/contour_features.h"

namespace contour_reg {

struct RefinementParams {
  bool enabled = true;
  int max_iterations = 12;
  double max_distance = 0.3;   ///< m, pairing distance in the first iteration
  double min_distance = 0.08;  ///< m, pairing distance it shrinks to
  /// The refinement stops once the pairing distance has shrunk to min_distance and a step
  /// moves the pose by less than stop_translation (m) and turns it by less than stop_rotation (rad).
  double stop_translation = 1e-4;
  double stop_rotation = 1e-5;

  bool validate(std::string *why = nullptr) const;
};

/// How the refinement samples and weighs the contours and what its covariance counts. It is
/// part of the method, not a setting: calibrated on simulated rooms and on the real relation
/// logs (docs/reliability.md) and the same for every LIDAR the project was measured with.
/// Studies of the covariance change it on a ContourRefiner.
struct RefinementModel {
  double sample_step = 0.1;         ///< m, spacing of the source samples along the contour
  double huber = 0.03;              ///< m, Huber threshold of the point-to-line residual
  double degeneracy_ratio = 0.005;  ///< smallest / largest eigenvalue below this is degenerate: no step along it
  /// The covariance is sigma^2 H^-1 times this. Neighbouring samples share raw points (the
  /// equalization interpolates them), so their residuals are correlated: H counts the samples
  /// between two raw returns farther apart than sample_step once per sample_step of their
  /// spacing, and this scale covers the correlation that remains where returns are dense
  /// (mean normalised error squared 1.7-2.8 on simulated rooms, tests/core/degeneracy_test.cc).
  double covariance_scale = 1.2;
  /// rad of yaw standard deviation per rad of turn, added to the covariance in quadrature:
  /// errors that grow with the turn and that the contours cannot show (a scan skewed by the
  /// turn made while it was taken, a beam-angle scale). On the real relation logs the yaw
  /// error's standard deviation grows from 0.39 deg for turns under 5 deg to 0.66 deg for
  /// turns of 20-45 deg (fr079): about 2 % of the turn.
  double turn_noise = 0.02;
  /// m of target contour over which residuals are taken to share their errors (a wall's
  /// surface, a repeated detail, a bias of the scene). The covariance also covers how the
  /// stretches of this length disagree with one another: the cluster-robust (sandwich) estimate
  /// H^-1 (sum over stretches of g g^T) H^-1, g a stretch's gradient at the estimate, adds where
  /// it exceeds the covariance above (docs/reliability.md). 0: off.
  double correlation_length = 1.0;

  bool validate(std::string *why = nullptr) const;
};

struct RefinementResult {
  Eigen::Matrix3d transform = Eigen::Matrix3d::Identity();  ///< source to target
  int pairs = 0;                                            ///< point-to-line pairs in the last iteration
  double rmse = 0.0;                                        ///< m, point-to-line, last iteration
  double overlap = 0.0;                                     ///< fraction of source samples paired in the last iteration
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();     ///< x, y, yaw
  /// The contours' information on x, y, yaw: the inverse of `covariance` before its turn term,
  /// kept because it is defined where the covariance is not (zero along a corridor's axis).
  Eigen::Matrix3d information = Eigen::Matrix3d::Zero();
  bool degenerate = false;  ///< some direction of (x, y, yaw) unconstrained by the contours
  /// Weakest over strongest eigenvalue of the translation information: 0 in a corridor,
  /// 1 when the contours constrain x and y alike.
  double constraint_ratio = 0.0;
  /// The rotation information left once translation is solved for (its Schur complement),
  /// over the most any contour at those ranges could give (every normal across the line of
  /// sight): 0 for a circle seen from inside, where turning about its centre changes nothing;
  /// 0.1 to 0.5 in rooms.
  double rotation_constraint_ratio = 0.0;
  /// m, RMS distance of the paired source points from the sensor: a turn of a radians moves
  /// them by about a * rms_range metres.
  double rms_range = 0.0;
  /// The motion (x m, y m, yaw rad) along which the contours constrain the estimate least: a
  /// corridor's axis, a turn about a circle's centre. Scaled so that it moves the source
  /// points by 1 m at rms_range. Zero when too few points were paired.
  Eigen::Vector3d weakest_direction = Eigen::Vector3d::Zero();
  int iterations = 0;
  /// Whether it ended at max_iterations still moving one way (its last two steps within 60 deg
  /// of each other, rotation in metres of arc): a slow slide, not yet converged. Ending in a
  /// back-and-forth between two pairings is not a slide.
  bool sliding = false;
};

/// A starting motion for the refinement (source to target, rigid) and the settings to refine it with.
struct RefinementStart {
  Eigen::Matrix3d motion;
  const RefinementParams *params;
};

/// The source points the refinement pairs: each contour's raw segment equalized centred
/// (equalizeCentred) at the whole number of elements nearest `sample_step` m; the contour's
/// own vertices, as many elements apart, for features without their segments.
std::vector<Eigen::Vector2d> contourSamples(const ContourFeatures &source, double sample_step);

/// The same into `samples`, reusing its buffer.
void contourSamples(const ContourFeatures &source, double sample_step, std::vector<Eigen::Vector2d> &samples);

/// Refines `initial` (source to target, rigid) on the contours of two scans.
RefinementResult refineOnContours(const ContourFeatures &source, const ContourFeatures &target,
                                  const Eigen::Matrix3d &initial, const RefinementParams &params,
                                  const RefinementModel &model = {});

/// Refines several starting motions against one target, whose search index it builds once.
/// It keeps working memory: one refiner serves one thread at a time.
class ContourRefiner {
 public:
  /// A refiner without a target: every refinement returns its start until setTarget().
  ContourRefiner();
  ContourRefiner(const ContourFeatures &target, const RefinementParams &params, const RefinementModel &model = {});
  /// Indexes a new target, reusing the buffers of the last one's index.
  void setTarget(const ContourFeatures &target);
  /// Refines with `model` from here on (a study of the covariance; RefinementModel{} by default).
  void setModel(const RefinementModel &model) { model_ = model; }
  const RefinementModel &model() const { return model_; }
  ~ContourRefiner();
  ContourRefiner(const ContourRefiner &) = delete;
  ContourRefiner &operator=(const ContourRefiner &) = delete;

  RefinementResult refine(const ContourFeatures &source, const Eigen::Matrix3d &initial) const;
  /// The same with other settings (a wider pairing distance for a rough start, say).
  RefinementResult refine(const ContourFeatures &source, const Eigen::Matrix3d &initial,
                          const RefinementParams &params) const;
  /// The same from the source's samples (contourSamples with model().sample_step), for several
  /// starting motions of one source. When `arrived` is given, the refinement stops as soon as
  /// it holds for the motion after an iteration: for a caller that asks only whether a start
  /// leads back to a motion it knows, the iterations after the refinement has come close to it
  /// cannot change that answer, only polish it.
  RefinementResult refine(const std::vector<Eigen::Vector2d> &samples, const Eigen::Matrix3d &initial,
                          const RefinementParams &params,
                          const std::function<bool(const Eigen::Matrix3d &)> &arrived = {}) const;
  /// Whether the refinement would pair `point` (target frame) with a target contour vertex
  /// within `distance` m.
  bool pairs(const Eigen::Vector2d &point, double distance) const;

 private:
  struct Index;
  std::unique_ptr<Index> index_;
  RefinementParams params_;
  RefinementModel model_;
};

}  // namespace contour_reg
