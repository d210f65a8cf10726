#include "contour_reg/core/registration.h"
#include "contour_reg/core/direction_histogram.h"

#include <algorithm>
#include <cmath>

namespace contour_reg {

namespace {

void fail(RegistrationResult &result, RegistrationStatus status, const std::string &reason) {
  result.converged = false;
  result.status = status;
  result.reason = reason;
}

// Fails after the refinement moved the transform: it goes back to the guess (identity without one).
void failAtGuess(RegistrationResult &result, const Eigen::Matrix3d *guess, RegistrationStatus status,
                 const std::string &reason) {
  result.transform = guess ? *guess : Eigen::Matrix3d::Identity();
  fail(result, status, reason);
}

// Pairs consistent with the guess: target near the guessed source position, rotation near its yaw.
std::vector<Correspondence> gateByGuess(const std::vector<Correspondence> &pairs,
                                        const std::vector<SpecialPoint> &source,
                                        const std::vector<SpecialPoint> &target, const Eigen::Matrix3d &guess,
                                        const RegistrationParams &params, bool check_rotation) {
  std::vector<Correspondence> kept;
  const double yaw = yawOf(guess);
  for (const Correspondence &c : pairs) {
    const Eigen::Vector2d predicted =
        guess.topLeftCorner<2, 2>() * source[c.source].position + guess.topRightCorner<2, 1>();
    if ((predicted - target[c.target].position).norm() > params.guess_max_distance) continue;
    if (check_rotation && std::abs(std::remainder(c.rotation - yaw, 2 * M_PI)) > params.guess_max_rotation) continue;
    kept.push_back(c);
  }
  return kept;
}

// Largest distance between two of the points.
double spread(const Points2D &points) {
  double widest = 0.0;
  for (std::size_t i = 0; i < points.size(); ++i)
    for (std::size_t j = i + 1; j < points.size(); ++j) widest = std::max(widest, (points[i] - points[j]).norm());
  return widest;
}

}  // namespace

bool RegistrationParams::validate(std::string *why) const {
  if (!correspondence.validate(why) || !ransac.validate(why) || !refinement.validate(why) ||
      !direction_histogram.validate(why) || !free_space.validate(why))
    return false;
  if (!(local_fallback_max_distance > 0.0)) {
    if (why) *why = "local_fallback_max_distance must be > 0";
    return false;
  }
  if (!(corner_min_overlap >= 0.0 && corner_min_overlap <= 1.0)) {
    if (why) *why = "corner_min_overlap must be in [0, 1]";
    return false;
  }
  if (!(probe_distance >= 0.0)) {
    if (why) *why = "probe_distance must be >= 0";
    return false;
  }
  if (probe_max_inliers < 0 || guess_check_max_inliers < 0) {
    if (why) *why = "probe_max_inliers and guess_check_max_inliers must be >= 0";
    return false;
  }
  if (min_special_points < 2 || min_inliers < 2) {
    if (why) *why = "min_special_points and min_inliers must be >= 2";
    return false;
  }
  return true;
}

const char *toString(RegistrationStatus status) {
  switch (status) {
    case RegistrationStatus::kConverged:
      return "converged";
    case RegistrationStatus::kInvalidParameters:
      return "invalid_parameters";
    case RegistrationStatus::kTooFewSpecialPoints:
      return "too_few_special_points";
    case RegistrationStatus::kTooFewCorrespondences:
      return "too_few_correspondences";
    case RegistrationStatus::kTooFewInliers:
      return "too_few_inliers";
    case RegistrationStatus::kDegenerate:
      return "degenerate";
    case RegistrationStatus::kLowOverlap:
      return "low_overlap";
    case RegistrationStatus::kUnconstrained:
      return "unconstrained";
    case RegistrationStatus::kAmbiguous:
      return "ambiguous";
  }
  return "unknown";
}

std::ostream &operator<<(std::ostream &out, RegistrationStatus status) { return out << toString(status); }

bool isUndecided(RegistrationStatus status) {
  return status != RegistrationStatus::kConverged && status != RegistrationStatus::kInvalidParameters;
}

namespace {

// The best of several starting motions refined on the contours, its score, and whether a
// distinct motion scores about as well (the scans cannot tell them apart).
struct BestRefinement {
  RefinementResult best;
  bool ambiguous = false;
  bool scored = false;  // whether `score` holds the best's score yet: it is computed when first needed
  double score = 0.0;
};

// Scores refined motions in one unit, a fraction of the contour: the share of the source
// contour the refinement paired (overlap) less the share of both contours the motion puts in
// the other scan's free space (free_space.h). Each scan's view is built on first use, so a
// registration that needs no comparison of motions builds none; the target's is kept in the
// buffers for the next call with the same target extraction.
class Scorer {
 public:
  Scorer(const ContourFeatures &source, const ContourFeatures &target, const FreeSpaceParams &params,
         RegistrationBuffers &buffers)
      : source_(source), target_(target), params_(params), buffers_(buffers) {}

  double contradiction(const Eigen::Matrix3d &motion) {
    if (!params_.enabled) return 0.0;
    if (!views_ready_) {
      if (target_.extraction == 0 || buffers_.viewed_target != target_.extraction) {
        buffers_.target_view.assign(target_);
        buffers_.viewed_target = target_.extraction;
      }
      buffers_.source_view.assign(source_);
      views_ready_ = true;
    }
    return mutualFreeSpaceEvidence(source_, buffers_.source_view, target_, buffers_.target_view, motion, params_)
        .fraction();
  }
  double score(const RefinementResult &refined) { return refined.overlap - contradiction(refined.transform); }
  double score(BestRefinement &found) {
    if (!found.scored) found.score = score(found.best);
    found.scored = true;
    return found.score;
  }

 private:
  const ContourFeatures &source_, &target_;
  const FreeSpaceParams &params_;
  RegistrationBuffers &buffers_;
  bool views_ready_ = false;
};

// The refiner of `buffers`, indexing `target` (rebuilt only for a different extraction).
const ContourRefiner &refinerFor(const ContourFeatures &target, RegistrationBuffers &buffers) {
  if (target.extraction == 0 || buffers.indexed_target != target.extraction) {
    buffers.refiner.setTarget(target);
    buffers.indexed_target = target.extraction;
  }
  return buffers.refiner;
}

// Refined motions whose scores (fractions of the contour) differ by less than this fit about as well.
constexpr double kOverlapTie = 0.05;

// How far apart two motions are: m, with 1 m per rad of turn.
double motionDistance(const Eigen::Matrix3d &a, const Eigen::Matrix3d &b) {
  return (a.topRightCorner<2, 1>() - b.topRightCorner<2, 1>()).norm() +
         std::abs(std::remainder(yawOf(a) - yawOf(b), 2.0 * M_PI));
}

// Motions farther apart than this (motionDistance) are distinct answers.
constexpr double kDistinctMotions = 0.2;

// The refinement settings for a start that may be far off (the guess): pairing begins at
// local_fallback_max_distance.
RefinementParams widened(const RegistrationParams &params) {
  RefinementParams wide = params.refinement;
  wide.max_distance = std::max(wide.max_distance, params.local_fallback_max_distance);
  return wide;
}

// The best score wins; where scores tie, the motion nearest the guess (no motion without
// one) wins. Many starts are first screened by a short, sparse refinement on overlap alone;
// the most promising few are refined in full and scored.
BestRefinement refineBest(const ContourFeatures &source, const ContourFeatures &target,
                          std::vector<RefinementStart> &starts, const Eigen::Matrix3d *guess,
                          RegistrationBuffers &buffers, Scorer &scorer) {
  const ContourRefiner &refiner = refinerFor(target, buffers);
  // The starts share their sample spacing: the source is sampled once for the full
  // refinements and once, twice as sparse, for the screening.
  const double step = starts.front().params->sample_step;
  std::vector<Eigen::Vector2d> &samples = buffers.samples;
  contourSamples(source, step, samples);
  constexpr std::size_t kRefinedInFull = 3;
  if (starts.size() > kRefinedInFull) {
    std::vector<Eigen::Vector2d> &sparse = buffers.sparse_samples;
    contourSamples(source, 2.0 * step, sparse);
    struct Screened {
      double overlap;
      std::size_t start;
      Eigen::Matrix3d motion;  // after the short refinement
    };
    std::vector<Screened> screened;
    for (std::size_t k = 0; k < starts.size(); ++k) {
      RefinementParams quick = *starts[k].params;
      quick.max_iterations = 2;
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
                       [&](const Screened *c) { return motionDistance(c->motion, s.motion) < 0.1; }))
        chosen.push_back(&s);
    }
    std::vector<RefinementStart> kept;
    for (const Screened *c : chosen) kept.push_back(starts[c->start]);
    starts = kept;
  }
  std::vector<RefinementResult> &refined = buffers.refined;
  refined.clear();
  for (const RefinementStart &start : starts)
    refined.push_back(refiner.refine(samples, rigidPart(start.motion), *start.params));
  if (refined.size() == 1) return BestRefinement{refined.front()};  // nothing to compare: scored when needed
  const Eigen::Matrix3d prior = guess ? rigidPart(*guess) : Eigen::Matrix3d::Identity();
  double scores[kRefinedInFull + 1];  // starts hold at most kRefinedInFull here, or fewer to begin with
  for (std::size_t k = 0; k < refined.size(); ++k) scores[k] = scorer.score(refined[k]);
  std::size_t best = 0;
  for (std::size_t k = 1; k < refined.size(); ++k) {
    const bool better = scores[k] > scores[best] + kOverlapTie ||
                        (scores[k] > scores[best] - kOverlapTie &&
                         motionDistance(refined[k].transform, prior) < motionDistance(refined[best].transform, prior));
    if (better) best = k;
  }
  BestRefinement result{refined[best], false, true, scores[best]};
  for (std::size_t k = 0; k < refined.size(); ++k)
    if (scores[k] > scores[best] - kOverlapTie &&
        motionDistance(refined[k].transform, refined[best].transform) > kDistinctMotions)
      result.ambiguous = true;
  return result;
}

// A probe has settled back when it ends within this fraction of the probe distance.
constexpr double kSettledBack = 0.25;

// Whether `best` is pinned along its weakest direction (RefinementResult::weakest_direction):
// started `probe` m off along it, both ways, the refinement of the source's `samples` against
// the `refiner`'s target must settle back on it, or at least fit worse where it settles. In a
// room the probes come back or lose overlap; a bare corridor, a circle turned about its
// centre, a corridor whose axis only a small stub constrains leave them elsewhere with as
// good a fit. A probe distance of 0 turns the check off.
bool settlesBack(BestRefinement &found, double probe, const RefinementParams &params, const ContourRefiner &refiner,
                 const std::vector<Eigen::Vector2d> &samples, Scorer &scorer) {
  const RefinementResult &best = found.best;
  if (!(probe > 0.0)) return true;
  if (best.weakest_direction.isZero()) return false;
  // Each probe starts `probe` m off: its first pairing distance reaches that much further.
  RefinementParams from_probe = params;
  from_probe.max_distance = params.max_distance + probe;
  const double x = best.transform(0, 2), y = best.transform(1, 2), yaw = yawOf(best.transform);
  for (const double sign : {1.0, -1.0}) {
    const Eigen::Vector3d off = sign * probe * best.weakest_direction;
    const RefinementResult r =
        refiner.refine(samples, rigidTransform(x + off(0), y + off(1), yaw + off(2)), from_probe);
    // How far from `best` the probe settled, rotation in metres of arc.
    const double left = Eigen::Vector3d(r.transform(0, 2) - x, r.transform(1, 2) - y,
                                        std::remainder(yawOf(r.transform) - yaw, 2.0 * M_PI) * best.rms_range)
                            .norm();
    if (left > kSettledBack * probe && scorer.score(r) > scorer.score(found) - kOverlapTie) return false;
  }
  return true;
}

// The contours' own answer: the guess (none: no motion) refined from the wider pairing distance.
RefinementResult refineFromGuess(const RegistrationParams &params, const Eigen::Matrix3d *guess,
                                 const ContourRefiner &refiner, const std::vector<Eigen::Vector2d> &samples) {
  return refiner.refine(samples, guess ? rigidPart(*guess) : Eigen::Matrix3d::Identity(), widened(params));
}

// Whether `best` stands against the motion the contours settle on from the guess: they agree,
// or that motion scores clearly worse. A few corners along repeated structure (a door every few
// metres) can match one period off, where the contours fit about as well as at the true motion.
bool standsAgainstGuess(BestRefinement &found, const RefinementResult &from_guess, Scorer &scorer) {
  return motionDistance(found.best.transform, from_guess.transform) <= kDistinctMotions ||
         scorer.score(from_guess) <= scorer.score(found) - kOverlapTie;
}

// Empties `result`, keeping the buffers of its lists.
void reset(RegistrationResult &result) {
  std::vector<Correspondence> candidates = std::move(result.candidates);
  std::vector<int> inliers = std::move(result.inliers);
  std::string reason = std::move(result.reason);
  result = RegistrationResult{};
  candidates.clear();
  inliers.clear();
  reason.clear();
  result.candidates = std::move(candidates);
  result.inliers = std::move(inliers);
  result.reason = std::move(reason);
}

void registerByCorners(const ContourFeatures &source, const ContourFeatures &target, const RegistrationParams &params,
                       std::mt19937 &rng, const Eigen::Matrix3d *guess, RegistrationBuffers &buffers,
                       RegistrationResult &result) {
  reset(result);
  if (guess) result.transform = *guess;
  std::string why;
  if (!params.validate(&why)) return fail(result, RegistrationStatus::kInvalidParameters, why);
  const auto &src = source.special_points, &dst = target.special_points;
  result.source_points = src.size();
  result.target_points = dst.size();
  const std::size_t needed = static_cast<std::size_t>(params.min_special_points);
  if (src.size() < needed || dst.size() < needed)
    return fail(result, RegistrationStatus::kTooFewSpecialPoints,
                "too few special points: " + std::to_string(src.size()) + " in source, " + std::to_string(dst.size()) +
                    " in target, need " + std::to_string(needed));

  // Stage D: candidate pairs by fragment distance (eq. 14).
  const bool invariant = params.correspondence.distance == FragmentDistance::kModulus;
  if (!invariant && guess) {
    std::vector<SpecialPoint> turned = src;  // pre-rotate by the guess for the Re form
    const Complex rotation = std::polar(1.0, yawOf(*guess));
    for (SpecialPoint &point : turned)
      for (Complex &v : point.fragment) v *= rotation;
    findCorrespondences(turned, dst, params.correspondence, result.candidates, buffers.correspondence);
  } else {
    findCorrespondences(src, dst, params.correspondence, result.candidates, buffers.correspondence);
  }
  if (guess && params.guess_max_distance > 0.0)
    result.candidates = gateByGuess(result.candidates, src, dst, *guess, params, invariant);
  const std::size_t sample = params.ransac.model == TransformModel::kRigid ? 2 : 3;
  if (result.candidates.size() < sample)
    return fail(result, RegistrationStatus::kTooFewCorrespondences,
                "too few candidate pairs: " + std::to_string(result.candidates.size()));

  // Stages E-F: RANSAC over the pairs.
  Points2D &p = buffers.pair_sources, &q = buffers.pair_targets;
  std::vector<double> &rotations = buffers.pair_rotations;
  p.clear();
  q.clear();
  rotations.clear();
  for (const Correspondence &c : result.candidates) {
    p.push_back(src[c.source].position);
    q.push_back(dst[c.target].position);
    rotations.push_back(c.rotation);
  }
  RansacResult &found = buffers.ransac_result;
  ransac(p, q, rotations, params.ransac, rng, found, buffers.ransac);
  result.ransac_iterations = found.iterations;
  result.inliers.assign(found.inliers.begin(), found.inliers.end());
  result.inlier_rmse = found.rmse;
  // Count distinct special points: one corner paired twice is no extra support.
  Points2D &inlier_sources = buffers.inlier_sources;
  inlier_sources.clear();
  for (int i : found.inliers)
    if (std::none_of(inlier_sources.begin(), inlier_sources.end(),
                     [&](const Eigen::Vector2d &x) { return (x - p[i]).norm() < 1e-9; }))
      inlier_sources.push_back(p[i]);
  // Support must exceed the minimal sample, which any model fits exactly.
  const std::size_t min_inliers = std::max<std::size_t>(params.min_inliers, sample + 1);
  const bool verify_two = params.two_inlier_min_overlap > 0.0 && params.refinement.enabled &&
                          params.ransac.model == TransformModel::kRigid && inlier_sources.size() == 2;
  if (!found.found || (inlier_sources.size() < min_inliers && !verify_two))
    return fail(result, RegistrationStatus::kTooFewInliers,
                "too few inliers: " + std::to_string(inlier_sources.size()) + " of " +
                    std::to_string(result.candidates.size()) + " pairs, need " + std::to_string(min_inliers));
  if (spread(inlier_sources) < params.min_inlier_spread)
    return fail(result, RegistrationStatus::kDegenerate, "inlier special points lie too close together");
  if (params.ransac.model == TransformModel::kAffine) {
    Eigen::Matrix3d check;
    if (!estimateAffine(inlier_sources, inlier_sources, check))
      return fail(result, RegistrationStatus::kDegenerate, "inlier special points are collinear");
  }

  // Beyond the paper: refine the rigid part on the contours.
  // With the affine model, RANSAC chose the inliers; the rigid fit on them starts the refinement.
  Eigen::Matrix3d coarse = found.transform;
  if (params.ransac.model == TransformModel::kAffine) {
    Points2D in_p, in_q;
    for (int i : found.inliers) {
      in_p.push_back(p[i]);
      in_q.push_back(q[i]);
    }
    if (!estimateRigid(in_p, in_q, coarse)) coarse = rigidPart(found.transform);
  }
  result.transform = params.ransac.model == TransformModel::kRigid ? coarse : found.transform;
  if (params.refinement.enabled) {
    // RANSAC may end with rival motions as well supported as its best (a symmetric room
    // seen from two corners matched crosswise): each is refined, and the contours decide.
    std::vector<RefinementStart> &starts = buffers.starts;
    starts.assign(1, {coarse, &params.refinement});
    for (const Eigen::Matrix3d &rival : found.rivals) starts.push_back({rival, &params.refinement});
    Scorer scorer(source, target, params.free_space, buffers);
    BestRefinement found = refineBest(source, target, starts, guess, buffers, scorer);
    const RefinementResult &refined = found.best;
    result.contour_rmse = refined.rmse;
    result.overlap = refined.overlap;
    result.covariance = refined.covariance;
    const std::size_t corners = inlier_sources.size();
    // Three corners or more pin every direction; fewer leave it to the contours.
    result.degenerate = refined.degenerate && corners < 3;
    result.transform = refined.transform;
    // The contours must confirm what the corners agree on; a motion they do not confirm goes
    // back to the guess, and the local fallback decides.
    auto decline = [&](const std::string &why) {
      failAtGuess(result, guess, RegistrationStatus::kTooFewInliers,
                  "too few inliers: " + std::to_string(corners) + " special points" + why);
    };
    // Two corners need a large overlap, more a modest one.
    if (refined.overlap < (verify_two ? params.two_inlier_min_overlap : params.corner_min_overlap))
      return decline(" agree, but the contours overlap only " +
                     std::to_string(static_cast<int>(100 * refined.overlap)) + " % after alignment");
    // A few corners, often along one wall, pin the motion no better than they are spread:
    // the contours must pin it too.
    if (corners <= static_cast<std::size_t>(params.probe_max_inliers) &&
        !settlesBack(found, params.probe_distance, params.refinement, buffers.refiner, buffers.samples, scorer))
      return decline(", and the contours leave a direction weakly constrained");
    if (corners <= static_cast<std::size_t>(params.guess_check_max_inliers) &&
        !standsAgainstGuess(found, refineFromGuess(params, guess, buffers.refiner, buffers.samples), scorer))
      return decline(", and the contours fit a distinct motion from the guess as well");
  }
  result.converged = true;
  result.status = RegistrationStatus::kConverged;
  result.reason.clear();
}

// Few corners: the guess, a motion one pair of corners implies, or a motion the contours'
// directions suggest, refined on the contours and kept when well supported and unambiguous.
constexpr std::size_t kMaxPairHypotheses = 8;
void tryLocalFallback(const ContourFeatures &source, const ContourFeatures &target, const RegistrationParams &params,
                      const Eigen::Matrix3d *guess, RegistrationBuffers &buffers, RegistrationResult &result) {
  // The guess may be far off: it is refined from a wider pairing distance.
  const RefinementParams wide = widened(params);
  std::vector<RefinementStart> starts{{guess ? rigidPart(*guess) : Eigen::Matrix3d::Identity(), &wide}};
  // Each candidate pair of corners is a full hypothesis on its own: the rotation arg (N, G)
  // of eq. (14) and the translation that brings the two corners together.
  if (params.correspondence.distance == FragmentDistance::kModulus) {
    std::vector<Correspondence> found_pairs;  // only when the corners stopped before pairing
    if (result.candidates.empty())
      found_pairs = findCorrespondences(source.special_points, target.special_points, params.correspondence);
    const std::vector<Correspondence> &pairs = result.candidates.empty() ? found_pairs : result.candidates;
    for (std::size_t k = 0; k < pairs.size() && k < kMaxPairHypotheses; ++k) {
      const Correspondence &c = pairs[k];
      const Eigen::Matrix3d turn = rigidTransform(0.0, 0.0, c.rotation);
      const Eigen::Vector2d moved = target.special_points[c.target].position -
                                    turn.topLeftCorner<2, 2>() * source.special_points[c.source].position;
      starts.push_back({rigidTransform(moved.x(), moved.y(), c.rotation), &params.refinement});
    }
  }
  if (params.direction_hypotheses)
    for (const Eigen::Matrix3d &motion : directionHypotheses(source, target, params.direction_histogram, guess))
      starts.push_back({motion, &params.refinement});

  Scorer scorer(source, target, params.free_space, buffers);
  BestRefinement found = refineBest(source, target, starts, guess, buffers, scorer);
  const RefinementResult &refined = found.best;
  if (refined.overlap < params.local_fallback_min_overlap) {
    result.status = RegistrationStatus::kLowOverlap;
    result.reason += "; refined on the contours, at best " + std::to_string(static_cast<int>(100 * refined.overlap)) +
                     " % of the source contour lies on the target";
    return;
  }
  if (refined.degenerate ||
      !settlesBack(found, params.probe_distance, params.refinement, buffers.refiner, buffers.samples, scorer)) {
    result.status = RegistrationStatus::kUnconstrained;
    result.reason += "; refined on the contours, a direction stays weakly constrained (corridor, circle)";
    return;
  }
  if (found.ambiguous) {
    result.status = RegistrationStatus::kAmbiguous;
    result.reason += "; refined on the contours, distinct motions fit equally well (repeated structure)";
    return;
  }
  result.transform = refined.transform;
  result.contour_rmse = refined.rmse;
  result.overlap = refined.overlap;
  result.covariance = refined.covariance;
  result.degenerate = false;
  result.from_local_fallback = true;
  result.converged = true;
  result.status = RegistrationStatus::kConverged;
  result.reason.clear();
}

}  // namespace

RegistrationResult registerContours(const ContourFeatures &source, const ContourFeatures &target,
                                    const RegistrationParams &params, std::mt19937 &rng, const Eigen::Matrix3d *guess) {
  RegistrationBuffers buffers;
  RegistrationResult result;
  registerContours(source, target, params, rng, guess, buffers, result);
  return result;
}

RegistrationResult registerContours(const ContourFeatures &source, const ContourFeatures &target,
                                    const RegistrationParams &params, std::mt19937 &rng, const Eigen::Matrix3d *guess,
                                    RegistrationBuffers &buffers) {
  RegistrationResult result;
  registerContours(source, target, params, rng, guess, buffers, result);
  return result;
}

void registerContours(const ContourFeatures &source, const ContourFeatures &target, const RegistrationParams &params,
                      std::mt19937 &rng, const Eigen::Matrix3d *guess, RegistrationBuffers &buffers,
                      RegistrationResult &result) {
  registerByCorners(source, target, params, rng, guess, buffers, result);
  if (!result.converged && isUndecided(result.status) && params.local_fallback_min_overlap > 0.0 &&
      params.refinement.enabled && !source.contours.empty() && !target.contours.empty())
    tryLocalFallback(source, target, params, guess, buffers, result);
}

}  // namespace contour_reg
