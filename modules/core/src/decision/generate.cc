#include "generate.h"

#include <algorithm>

#include "contour_reg/core/direction_histogram.h"
#include "contour_reg/core/transform_estimation.h"

namespace contour_reg::decision {

namespace {

// Candidate pairs of corners taken as hypotheses of their own: the first in the order found (the
// source points in bearing order, each one's candidates best first).
constexpr std::size_t kMaxPairHypotheses = 8;

}  // namespace

RefinementParams widened(const RegistrationParams &params, const Checks &checks) {
  RefinementParams wide = params.refinement;
  wide.max_distance = std::max(wide.max_distance, checks.local_fallback_max_distance);
  return wide;
}

void cornerHypotheses(const Eigen::Matrix3d &coarse, const std::vector<Eigen::Matrix3d> &rivals,
                      const RefinementParams &params, std::vector<RefinementStart> &starts) {
  starts.assign(1, {coarse, &params});
  for (const Eigen::Matrix3d &rival : rivals) starts.push_back({rival, &params});
}

void contourHypotheses(const ContourFeatures &source, const ContourFeatures &target, const RegistrationParams &params,
                       const Checks &checks, const Eigen::Matrix3d *guess, const std::vector<Correspondence> &pairs,
                       const RefinementParams &wide, std::vector<RefinementStart> &starts) {
  starts.assign(1, {guess ? rigidPart(*guess) : Eigen::Matrix3d::Identity(), &wide});
  // A single pair fixes the motion only with the rotation-invariant fragment distance, whose
  // correspondences carry the rotation.
  if (params.correspondence.distance == FragmentDistance::kModulus) {
    std::vector<Correspondence> found;  // only when the corners stopped before pairing
    if (pairs.empty()) found = findCorrespondences(source.special_points, target.special_points, params.correspondence);
    const std::vector<Correspondence> &used = pairs.empty() ? found : pairs;
    for (std::size_t k = 0; k < used.size() && k < kMaxPairHypotheses; ++k) {
      const Correspondence &c = used[k];
      const Eigen::Matrix3d turn = rigidTransform(0.0, 0.0, c.rotation);
      const Eigen::Vector2d moved = target.special_points[c.target].position -
                                    turn.topLeftCorner<2, 2>() * source.special_points[c.source].position;
      starts.push_back({rigidTransform(moved.x(), moved.y(), c.rotation), &params.refinement});
    }
  }
  if (checks.direction_hypotheses)
    for (const Eigen::Matrix3d &motion : directionHypotheses(source, target, DirectionHistogramParams{}, guess))
      starts.push_back({motion, &params.refinement});
}

}  // namespace contour_reg::decision
