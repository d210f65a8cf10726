#pragma once
/// @file generate.h
/// The decision, stage 1 of 4 (generate, refine, score, judge): candidate motions.
///
/// Every candidate is a starting motion for the contour refinement (RefinementStart). Two
/// sets exist:
/// - the corners' hypotheses: RANSAC's best motion and its rivals, motions as well supported
///   by distinct pairs of special points (a symmetric room seen from two corners matched
///   crosswise);
/// - the contours' hypotheses, when the corners do not decide: the guess (identity without
///   one), the motion each of the first candidate pairs of corners implies on its own (the
///   rotation arg(N, G) of eq. 14 and the translation that brings the two corners together),
///   and the motions the contours' directions and wall offsets suggest (direction_histogram.h).
///   The corners' motion the judge declined, already refined and scored, joins them when it
///   is distinct from their best and scores clearly better (registration.cc): their starts
///   did not reach the motion the contours fit best.

#include <vector>

#include <Eigen/Core>

#include "checks.h"
#include "contour_reg/core/contour_features.h"
#include "contour_reg/core/correspondence.h"
#include "contour_reg/core/refinement.h"
#include "contour_reg/core/registration.h"

namespace contour_reg::decision {

/// The refinement settings for a start that may be far off (the guess): pairing begins at
/// Checks::local_fallback_max_distance.
RefinementParams widened(const RegistrationParams &params, const Checks &checks);

/// RANSAC's best motion `coarse` and its `rivals`, each refined with `params`, into `starts`.
void cornerHypotheses(const Eigen::Matrix3d &coarse, const std::vector<Eigen::Matrix3d> &rivals,
                      const RefinementParams &params, std::vector<RefinementStart> &starts);

/// The contours' hypotheses into `starts`. `pairs` are the candidate pairs of special points
/// already found (empty: they are found here); `wide` (widened(params, checks)) refines the
/// guess and must outlive the starts.
void contourHypotheses(const ContourFeatures &source, const ContourFeatures &target, const RegistrationParams &params,
                       const Checks &checks, const Eigen::Matrix3d *guess, const std::vector<Correspondence> &pairs,
                       const RefinementParams &wide, std::vector<RefinementStart> &starts);

}  // namespace contour_reg::decision
