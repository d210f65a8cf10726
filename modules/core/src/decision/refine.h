#pragma once
/// @file refine.h
/// The decision, stage 2 of 4 (generate, refine, score, judge): the candidates refined on the contours.
///
/// Each candidate motion is refined point-to-line on the contours (refinement.h). With more
/// candidates than kRefinedInFull, a cheap screening pass comes first: two iterations on a
/// source sampled twice as sparse, ranked by overlap; the best few that lead to distinct motions
/// are then refined in full. Hard pairs with many hypotheses stay fast this way.

#include <vector>

#include "contour_reg/core/contour_features.h"
#include "contour_reg/core/refinement.h"
#include "contour_reg/core/registration.h"

namespace contour_reg::decision {

/// Candidates refined in full at most.
constexpr std::size_t kRefinedInFull = 3;

/// Iterations of a screening pass, on the source sampled twice as sparse: enough to show
/// where a start leads and how well it fits there.
constexpr int kScreeningIterations = 2;

/// The refiner of `buffers`, indexing `target` (rebuilt only for a different extraction).
const ContourRefiner &refinerFor(const ContourFeatures &target, RegistrationBuffers &buffers);

/// The source samples `sample_step` apart (contourSamples) in `samples`, computed again only
/// for a different extraction or step than `sampled` records.
const std::vector<Eigen::Vector2d> &samplesOf(const ContourFeatures &source, double sample_step,
                                              std::vector<Eigen::Vector2d> &samples,
                                              std::pair<std::uint64_t, double> &sampled);

/// The source samples twice as sparse as the refiner's (the refiner of `buffers` with its
/// model's sample_step), kept in buffers.sparse_samples: what the screening passes refine.
const std::vector<Eigen::Vector2d> &screeningSamplesOf(const ContourFeatures &source, RegistrationBuffers &buffers);

/// Refines the most promising of `starts` (kept in `starts`) in full into buffers.refined, in
/// the order of `starts`; buffers.samples then holds the source samples they were refined on.
const std::vector<RefinementResult> &refineHypotheses(const ContourFeatures &source, const ContourFeatures &target,
                                                      std::vector<RefinementStart> &starts,
                                                      RegistrationBuffers &buffers);

}  // namespace contour_reg::decision
