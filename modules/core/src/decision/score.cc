#include "score.h"

#include <cmath>

#include "contour_reg/core/transform_estimation.h"

namespace contour_reg::decision {

double Scorer::contradiction(const Eigen::Matrix3d &motion) {
  const auto [seen_by_target, seen_by_source] = evidenceEachWay(motion);
  return (seen_by_target + seen_by_source).fraction();
}

std::pair<FreeSpaceEvidence, FreeSpaceEvidence> Scorer::evidenceEachWay(const Eigen::Matrix3d &motion) {
  if (!params_.enabled) return {};
  prepareViews();
  return {freeSpaceEvidence(source_, buffers_.target_view, motion, params_),
          freeSpaceEvidence(target_, buffers_.source_view, rigidInverse(motion), params_)};
}

namespace {

// Builds `view` of the target's `seen` (its contours or its returns), unless `viewed` says it
// already shows this extraction of the target (extraction 0: never kept).
template <class Seen>
void viewTarget(const ContourFeatures &target, const Seen &seen, RangeView &view, std::uint64_t &viewed) {
  if (target.extraction != 0 && viewed == target.extraction) return;
  view.assign(seen);
  viewed = target.extraction;
}

}  // namespace

void Scorer::prepareViews() {
  if (views_ready_) return;
  viewTarget(target_, target_, buffers_.target_view, buffers_.viewed_target);
  buffers_.source_view.assign(source_);
  views_ready_ = true;
}

void Scorer::prepareReturnViews() {
  if (returns_views_ready_) return;
  viewTarget(target_, target_.returns, buffers_.target_returns_view, buffers_.returns_viewed_target);
  buffers_.source_returns_view.assign(source_.returns);
  returns_views_ready_ = true;
}

double Scorer::contradictedReturns(const Eigen::Matrix3d &motion) {
  if (!params_.enabled) return 0.0;
  prepareReturnViews();
  return contradictedReturnShare(source_.returns, buffers_.target_returns_view, target_.returns,
                                 buffers_.source_returns_view, motion, params_.margin);
}

const RangeView &Scorer::targetView() {
  prepareViews();
  return buffers_.target_view;
}

const RangeView &Scorer::targetReturnsView() {
  prepareReturnViews();
  return buffers_.target_returns_view;
}

double Scorer::score(ScoredMotion &motion) {
  if (!motion.scored) motion.score = score(motion.refined);
  motion.scored = true;
  return motion.score;
}

}  // namespace contour_reg::decision
