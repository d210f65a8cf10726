#include "refine.h"

#include <algorithm>

#include "contour_reg/core/transform_estimation.h"
#include "score.h"

namespace contour_reg::decision {

const ContourRefiner &refinerFor(const ContourFeatures &target, RegistrationBuffers &buffers) {
  if (target.extraction == 0 || buffers.indexed_target != target.extraction) {
    buffers.refiner.setTarget(target);
    buffers.indexed_target = target.extraction;
  }
  return buffers.refiner;
}

const std::vector<Eigen::Vector2d> &samplesOf(const ContourFeatures &source, double sample_step,
                                              std::vector<Eigen::Vector2d> &samples,
                                              std::pair<std::uint64_t, double> &sampled) {
  if (source.extraction == 0 || sampled != std::make_pair(source.extraction, sample_step)) {
    contourSamples(source, sample_step, samples);
    sampled = {source.extraction, sample_step};
  }
  return samples;
}

const std::vector<Eigen::Vector2d> &screeningSamplesOf(const ContourFeatures &source, RegistrationBuffers &buffers) {
  return samplesOf(source, 2.0 * buffers.refiner.model().sample_step, buffers.sparse_samples, buffers.sparse_sampled);
}

const std::vector<RefinementResult> &refineHypotheses(const ContourFeatures &source, const ContourFeatures &target,
                                                      std::vector<RefinementStart> &starts,
                                                      RegistrationBuffers &buffers) {
  const ContourRefiner &refiner = refinerFor(target, buffers);
  // The source is sampled once for the full refinements, at the refiner's spacing, and once,
  // twice as sparse, for the screening.
  const std::vector<Eigen::Vector2d> &samples =
      samplesOf(source, refiner.model().sample_step, buffers.samples, buffers.sampled);
  if (starts.size() > kRefinedInFull) {
    const std::vector<Eigen::Vector2d> &sparse = screeningSamplesOf(source, buffers);
    struct Screened {
      double overlap;
      std::size_t start;
      Eigen::Matrix3d motion;  // after the short refinement
    };
    std::vector<Screened> screened;
    for (std::size_t k = 0; k < starts.size(); ++k) {
      RefinementParams quick = *starts[k].params;
      quick.max_iterations = kScreeningIterations;
      const RefinementResult r = refiner.refine(sparse, rigidPart(starts[k].motion), quick);
      screened.push_back({r.overlap, k, r.transform});
    }
    std::stable_sort(screened.begin(), screened.end(),
                     [](const Screened &a, const Screened &b) { return a.overlap > b.overlap; });
    // The best few that lead to distinct motions: two starts bound for one motion test nothing new.
    std::vector<const Screened *> chosen;
    for (const Screened &s : screened) {
      if (chosen.size() == kRefinedInFull) break;
      if (std::none_of(chosen.begin(), chosen.end(),
                       [&](const Screened *c) { return motionDistance(c->motion, s.motion) < kDistinctMotions / 2; }))
        chosen.push_back(&s);
    }
    std::vector<RefinementStart> kept;
    for (const Screened *c : chosen) kept.push_back(starts[c->start]);
    starts = kept;
  }
  std::vector<RefinementResult> &refined = buffers.refined;
  refined.clear();
  for (const RefinementStart &start : starts) {
    refined.push_back(refiner.refine(samples, rigidPart(start.motion), *start.params));
    // A refinement that ran out of iterations still sliding one way goes on from where it
    // stopped, at the smallest pairing distance, as far again.
    if (refined.back().sliding) {
      RefinementParams on = *start.params;
      on.max_distance = on.min_distance;
      refined.back() = refiner.refine(samples, refined.back().transform, on);
    }
  }
  return refined;
}

}  // namespace contour_reg::decision
