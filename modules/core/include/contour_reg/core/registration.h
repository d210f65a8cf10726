#pragma once
/// @file registration.h
/// Stages D-F in one call, plus the contour refinement: the transform that maps a
/// source scan's contour features onto a target scan's.
///
/// Odometry matches each scan (source) against the previous one (target); the result
/// maps source coordinates into the target frame, q = H p, as PCL's Registration does.
/// "Converged" means a supported, non-degenerate estimate; otherwise `status` and
/// `reason` say why not, and the transform is the guess (or identity).
///
/// How it decides between candidate motions is four stages in modules/core/src/decision/:
/// generate (RANSAC's best and rivals; without a corner decision, the guess, single corner
/// pairs and the contour directions), refine (on the contours), score (contour overlap less
/// free-space contradiction) and judge (supported, pinned, unrivalled; or the verdict).

#include <cstdint>
#include <optional>
#include <ostream>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "contour_reg/core/contour_features.h"
#include "contour_reg/core/correspondence.h"
#include "contour_reg/core/free_space.h"
#include "contour_reg/core/ransac.h"
#include "contour_reg/core/refinement.h"

namespace contour_reg {

struct RegistrationParams {
  CorrespondenceParams correspondence;
  RansacParams ransac;
  RefinementParams refinement;
  /// Free-space evidence: where distinct motions compete (RANSAC's rivals, the probes, the
  /// guess's refinement, the local fallback's starts), each is scored by its contour overlap
  /// less the share of contour it puts in the other scan's free space (free_space.h), both
  /// fractions of the contour; a motion whose score trails the best by the tie margin is no rival.
  FreeSpaceParams free_space;
  int min_special_points = 2;  ///< per scan
  int min_inliers = 3;         ///< supporting pairs of distinct special points
  /// With a guess: pairs whose target lies farther than this from the guessed position
  /// of their source point, or whose rotation disagrees with the guess by more than
  /// guess_max_rotation, are dropped. <= 0 ignores the guess for pairing.
  double guess_max_distance = 0.0;
  double guess_max_rotation = 0.5;  ///< rad
  /// When the corners cannot decide (too few special points, pairs or inliers, or inliers
  /// too close together or collinear), refine on the contours the guess (identity without
  /// one), the motion each candidate pair of corners implies, and the motions the contour
  /// directions suggest (direction_histogram.h), and accept the best when at least this
  /// fraction of the source contour then lies on the target contour (three quarters of it
  /// when the beams of both scans agree with the motion, free_space.h), the contours pin it
  /// in every direction (probe_distance) and no distinct motion fits as well. <= 0 disables it:
  /// such pairs then fail. The result says when it came from here (from_local_fallback).
  double local_fallback_min_overlap = 0.4;
  /// m, the probe: the local fallback's motion, and a motion only a few corners agree on,
  /// refined again from this far off along its weakest direction
  /// (RefinementResult::weakest_direction), both ways, must settle back or fit worse where it
  /// settles, also on the part of the source within the target's field of view and range. A
  /// room or a corridor with a closed end passes; a bare corridor, a circle seen from inside,
  /// a corridor whose axis only a small stub constrains or whose end is out of range stay
  /// "not converged".
  /// The local fallback's motion must also be the best along that direction out to the scan's
  /// RMS range (a distinct motion there that fits as well: ambiguous). 0 skips both checks.
  double probe_distance = 0.2;

  bool validate(std::string *why = nullptr) const;
};

/// The verdict of a registration. The corners' verdicts come first (for a motion they agree
/// on, the judge's: low overlap, unconstrained, ambiguous, contradicted); when the local
/// fallback runs and finds no acceptable motion either, its verdict (one of the same four)
/// replaces theirs, and `reason` keeps both.
enum class RegistrationStatus {
  kConverged,
  kInvalidParameters,
  kTooFewSpecialPoints,    ///< a scan has fewer than min_special_points (a corridor of plain walls)
  kTooFewCorrespondences,  ///< too few candidate pairs of special points
  kTooFewInliers,          ///< the pairs agree on no motion with enough support
  kDegenerate,             ///< the inlier special points lie too close together or on a line
  kLowOverlap,             ///< on the contours, the best motion puts too little of the source on the target
  kUnconstrained,          ///< on the contours, a direction stays weakly constrained (a corridor, a circle)
  kAmbiguous,              ///< on the contours, a distinct motion scores as well (repeated structure, symmetry)
  kContradicted,           ///< the best motion puts contour where the other scan's beams saw through empty space
};

/// How far apart two motions are: m of translation plus rad of turn (1 m per rad).
double motionDistance(const Eigen::Matrix3d &a, const Eigen::Matrix3d &b);

/// Motions farther apart than this (motionDistance) are distinct answers: the one definition
/// every verdict uses (a rival, an ambiguous pair of motions, a probe that did not settle back).
constexpr double kDistinctMotions = 0.2;

/// A motion the judge weighed and did not return, for pictures, diagnosis and a prior to
/// decide between (RegistrationResult::alternatives).
struct RejectedMotion {
  Eigen::Matrix3d transform = Eigen::Matrix3d::Identity();  ///< source to target
  double overlap = 0.0;                                     ///< fraction of source contour the refinement paired
  /// The decision's score (decision/score.h): overlap less the share of both contours the
  /// motion puts in the other scan's free space.
  double score = 0.0;
  /// x, y, yaw: the refinement's covariance of the motion where the contours put it (as
  /// RegistrationResult::covariance of a converged one), zero where it has none.
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
};

/// A short name for a status ("converged", "too_few_special_points", ...).
const char *toString(RegistrationStatus status);
/// Writes toString(status).
std::ostream &operator<<(std::ostream &out, RegistrationStatus status);

/// True for the verdicts where the scans did not decide the motion: every status but
/// converged and invalid parameters. Another method, or a guess, may still decide it.
bool isUndecided(RegistrationStatus status);

/// What the contours pin of a motion when they leave one direction free (a corridor's axis, a
/// turn inside a circle): their best motion, and its information with that direction taken
/// out (marginalised: the free motion is left unknown). Alone it is no estimate; with a prior
/// that pins the free direction, such as wheel odometry (odometry/wheel_fusion.h), it is one.
struct PinnedMotion {
  Eigen::Matrix3d transform = Eigen::Matrix3d::Identity();  ///< source to target
  /// Information (inverse covariance) on x (m), y (m), yaw (rad); zero along free_direction.
  Eigen::Matrix3d information = Eigen::Matrix3d::Zero();
  /// The free direction (x m, y m, yaw rad), RefinementResult::weakest_direction.
  Eigen::Vector3d free_direction = Eigen::Vector3d::Zero();
};

struct RegistrationResult {
  Eigen::Matrix3d transform = Eigen::Matrix3d::Identity();  ///< source to target
  bool converged = false;
  RegistrationStatus status = RegistrationStatus::kTooFewSpecialPoints;
  std::string reason;                      ///< empty when converged
  std::size_t source_points = 0;           ///< special points in the source scan
  std::size_t target_points = 0;           ///< special points in the target scan
  std::vector<Correspondence> candidates;  ///< candidate pairs given to RANSAC
  std::vector<int> inliers;                ///< indices into `candidates`
  double inlier_rmse = 0.0;                ///< m, corner vertices of the inliers
  int ransac_iterations = 0;
  double contour_rmse = 0.0;  ///< m, point-to-line after refinement (0 without it)
  double overlap = 0.0;       ///< fraction of source contour paired by the refinement
  /// A converged estimate's score, as the judge weighed it against its rivals (RejectedMotion::score):
  /// `overlap` less the share of both contours the estimate puts in the other scan's free space.
  /// 0 when not converged (`rejected` holds the declined motion's) or without the refinement.
  double score = 0.0;
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();  ///< x, y, yaw of the estimate
  /// Some direction of the estimate is unconstrained: the contours leave it so (a corridor,
  /// a single wall) and fewer than three inlier corners pin it.
  bool degenerate = false;
  /// True when the corners could not decide and the estimate is the guess refined on the
  /// contours (a local answer: right only when the guess was close enough).
  bool from_local_fallback = false;
  /// Set when the contours' best motion leaves one direction free: an unconstrained verdict,
  /// or a converged estimate marked degenerate. `transform` stays the guess for the former.
  std::optional<PinnedMotion> pinned;
  /// The best-scoring motion the judge weighed and did not return: with a converged result,
  /// the best distinct rival it was compared with; otherwise the motion it declined. Not set
  /// when no refinement ran (refinement off, a scan without contours, or the corners without
  /// a motion and the local fallback off) or a converged motion met no distinct rival.
  std::optional<RejectedMotion> rejected;
  /// An ambiguous verdict's distinct motions that fit the scans about as well: the best, then
  /// the rival it ties with (a candidate within the score's tie, or one nearly as good that the
  /// beams side with), or every motion a period along repeated structure that ties with it,
  /// either way along it. The scans cannot tell them apart; a prior on the motion that allows
  /// one of them alone can (odometry's prediction over the interval does). Empty otherwise.
  std::vector<RejectedMotion> alternatives;
};

/// What registration keeps between calls: the target's refinement index, rebuilt only when
/// the target is a different extraction (ContourFeatures::extraction), and the working memory
/// of every stage. A caller that registers many pairs (odometry, many sources against one
/// target) keeps one and passes it to every call; once its buffers have grown, a registration
/// that the corners decide allocates nothing.
struct RegistrationBuffers {
  ContourRefiner refiner;
  std::uint64_t indexed_target = 0;  ///< extraction the refiner indexes (0: none)
  CorrespondenceScratch correspondence;
  RansacScratch ransac;
  RansacResult ransac_result;
  Points2D pair_sources, pair_targets, inlier_sources;
  std::vector<double> pair_rotations;
  std::vector<RefinementStart> starts;
  std::vector<RefinementResult> refined;
  std::vector<Eigen::Vector2d> samples, sparse_samples;
  /// The extraction and sample step `samples` and `sparse_samples` hold (extraction 0: none).
  std::pair<std::uint64_t, double> sampled{0, 0.0}, sparse_sampled{0, 0.0};
  RangeView target_view, source_view;  ///< each scan's view, for free-space evidence
  std::uint64_t viewed_target = 0;     ///< extraction target_view shows (0: none)
  /// Each scan's view of all its returns (ContourFeatures::returns), for the beam-by-beam evidence.
  RangeView target_returns_view, source_returns_view;
  std::uint64_t returns_viewed_target = 0;  ///< extraction target_returns_view shows (0: none)
  /// Working memory of the judge's check for repeated structure: the target's axis and its
  /// contour points across the axis and across the perpendicular (along, across each), kept
  /// while the target is the same extraction; the source's; the votes per lag, the lags found
  /// and the motions they shift to.
  struct Repetition {
    std::uint64_t crossed_target = 0;  ///< extraction the target's axis and crossings are of (0: none)
    Eigen::Vector2d axis = Eigen::Vector2d::UnitX();
    std::vector<Eigen::Vector2d> target_crossings[2], source_crossings[2];
    std::vector<double> votes;
    std::vector<std::pair<double, int>> peaks;
    std::vector<Eigen::Matrix3d> shifted;
  } repetition;
};

/// Registers `source` onto `target`. How the judge decides is fixed by the method
/// (modules/core/src/decision/checks.h); `params` say what the scans and the robot are. `guess` (source to target),
/// when given, is the fallback transform and the start of the local fallback; with guess_max_distance > 0 it gates the
/// pairs, and with the rotation-dependent FragmentDistance::kReal the source fragments are turned by its yaw before
/// comparing. With the affine model, RANSAC fits the paper's affine map; the refinement, when enabled, then refines its
/// rigid part and that is reported.
RegistrationResult registerContours(const ContourFeatures &source, const ContourFeatures &target,
                                    const RegistrationParams &params, std::mt19937 &rng,
                                    const Eigen::Matrix3d *guess = nullptr);

/// The same, keeping target-side work and buffers in `buffers` for the next call.
RegistrationResult registerContours(const ContourFeatures &source, const ContourFeatures &target,
                                    const RegistrationParams &params, std::mt19937 &rng, const Eigen::Matrix3d *guess,
                                    RegistrationBuffers &buffers);

/// The same into `result`, whose lists keep their buffers as well.
void registerContours(const ContourFeatures &source, const ContourFeatures &target, const RegistrationParams &params,
                      std::mt19937 &rng, const Eigen::Matrix3d *guess, RegistrationBuffers &buffers,
                      RegistrationResult &result);

}  // namespace contour_reg
