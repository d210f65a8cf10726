#pragma once
/// @file score.h
/// The decision, stage 3 of 4 (generate, refine, score, judge): one score per refined motion.
///
/// A refined motion scores the share of the source contour the refinement paired (its
/// overlap) less the share of both contours the motion puts in the other scan's free space
/// (free_space.h): one unit, a fraction of the contour. Overlap alone cannot tell a motion one
/// door off along a row of doors from the truth; the walls and doors it lands on the other
/// scan's seen-through space can. Motions whose scores differ by less than kScoreTie fit about
/// as well; motions farther apart than kDistinctMotions (motionDistance, registration.h) are
/// distinct answers.

#include <utility>

#include <Eigen/Core>

#include "contour_reg/core/contour_features.h"
#include "contour_reg/core/free_space.h"
#include "contour_reg/core/refinement.h"
#include "contour_reg/core/registration.h"

namespace contour_reg::decision {

/// Refined motions whose scores (fractions of the contour) differ by less than this fit about as well.
constexpr double kScoreTie = 0.05;

/// A refined motion and its score, computed when first needed.
struct ScoredMotion {
  RefinementResult refined;
  bool scored = false;
  double score = 0.0;
};

/// Scores refined motions of one pair of scans. Each scan's view (RangeView) is built on
/// first use, so a registration that compares no motions builds none; the target's is kept in
/// the buffers for the next call with the same target extraction.
class Scorer {
 public:
  Scorer(const ContourFeatures &source, const ContourFeatures &target, const FreeSpaceParams &params,
         RegistrationBuffers &buffers)
      : source_(source), target_(target), params_(params), buffers_(buffers) {}

  /// The share of both contours `motion` puts in the other scan's free space (0 with free space off).
  double contradiction(const Eigen::Matrix3d &motion);
  /// Overlap less contradiction.
  double score(const RefinementResult &refined) { return refined.overlap - contradiction(refined.transform); }
  double score(ScoredMotion &motion);
  /// The free-space evidence against `motion` each way: the source's contour in the target's
  /// view, the target's in the source's (none with free space off).
  std::pair<FreeSpaceEvidence, FreeSpaceEvidence> evidenceEachWay(const Eigen::Matrix3d &motion);

  /// The share of both scans' returns, beam by beam, that `motion` puts in the other scan's
  /// free space (contradictedReturnShare; 0 with free space off).
  double contradictedReturns(const Eigen::Matrix3d &motion);

  /// The target's view of its contours (built on first use, free space on or off).
  const RangeView &targetView();
  /// The target's view of all its returns, isolated ones too (built on first use, free space
  /// on or off).
  const RangeView &targetReturnsView();

  const ContourFeatures &source() const { return source_; }
  const ContourFeatures &target() const { return target_; }

 private:
  const ContourFeatures &source_, &target_;
  const FreeSpaceParams &params_;
  RegistrationBuffers &buffers_;
  bool views_ready_ = false, returns_views_ready_ = false;
  void prepareViews();
  void prepareReturnViews();  // the views of all returns, for contradictedReturns
};

}  // namespace contour_reg::decision
