#include "contour_reg/core/registration.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "decision/checks.h"
#include "decision/generate.h"
#include "decision/judge.h"
#include "decision/refine.h"
#include "decision/score.h"

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
    const Eigen::Vector2d predicted = transformPoint(guess, source[c.source].position);
    if ((predicted - target[c.target].position).norm() > params.guess_max_distance) continue;
    if (check_rotation && std::abs(std::remainder(c.rotation - yaw, 2 * M_PI)) > params.guess_max_rotation) continue;
    kept.push_back(c);
  }
  return kept;
}

// `motion` as RegistrationResult::rejected reports it.
RejectedMotion rejected(decision::ScoredMotion &motion, decision::Scorer &scorer) {
  return {motion.refined.transform, motion.refined.overlap, scorer.score(motion), motion.refined.covariance};
}

// Keeps `motion` in result.rejected when it scores higher than the motion there.
void offerRejected(RegistrationResult &result, const RejectedMotion &motion) {
  if (!result.rejected || motion.score > result.rejected->score) result.rejected = motion;
}

// An ambiguous verdict's alternatives: `best`, then every motion a period along repeated
// structure that ties with it, or else the rival it ties with.
void nameAlternatives(RegistrationResult &result, const RejectedMotion &best, decision::Judged &judged,
                      decision::Scorer &scorer) {
  result.alternatives = {best};
  for (decision::ScoredMotion &tie : judged.ties) result.alternatives.push_back(rejected(tie, scorer));
  if (judged.ties.empty() && judged.rival) result.alternatives.push_back(rejected(*judged.rival, scorer));
  if (result.alternatives.size() < 2) result.alternatives.clear();
}

// Largest distance between two of the points.
double spread(const Points2D &points) {
  double widest = 0.0;
  for (std::size_t i = 0; i < points.size(); ++i)
    for (std::size_t j = i + 1; j < points.size(); ++j) widest = std::max(widest, (points[i] - points[j]).norm());
  return widest;
}

}  // namespace

bool decision::Checks::validate(std::string *why) const {
  if (!(local_fallback_max_distance > 0.0)) {
    if (why) *why = "local_fallback_max_distance must be > 0";
    return false;
  }
  if (!(corner_min_overlap >= 0.0 && corner_min_overlap <= 1.0)) {
    if (why) *why = "corner_min_overlap must be in [0, 1]";
    return false;
  }
  if (!(beam_agreed_overlap_share >= 0.0 && beam_agreed_overlap_share <= 1.0)) {
    if (why) *why = "beam_agreed_overlap_share must be in [0, 1]";
    return false;
  }
  if (probe_max_inliers < 0 || guess_check_max_inliers < 0) {
    if (why) *why = "probe_max_inliers and guess_check_max_inliers must be >= 0";
    return false;
  }
  return refinement_model.validate(why);
}

bool RegistrationParams::validate(std::string *why) const {
  if (!correspondence.validate(why) || !ransac.validate(why) || !refinement.validate(why) || !free_space.validate(why))
    return false;
  if (!(probe_distance >= 0.0)) {
    if (why) *why = "probe_distance must be >= 0";
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
    case RegistrationStatus::kContradicted:
      return "contradicted";
  }
  return "unknown";
}

std::ostream &operator<<(std::ostream &out, RegistrationStatus status) { return out << toString(status); }

double motionDistance(const Eigen::Matrix3d &a, const Eigen::Matrix3d &b) {
  return (a.topRightCorner<2, 1>() - b.topRightCorner<2, 1>()).norm() +
         std::abs(std::remainder(yawOf(a) - yawOf(b), 2.0 * M_PI));
}

bool isUndecided(RegistrationStatus status) {
  return status != RegistrationStatus::kConverged && status != RegistrationStatus::kInvalidParameters;
}

namespace {

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
                       const decision::Checks &checks, std::mt19937 &rng, const Eigen::Matrix3d *guess,
                       RegistrationBuffers &buffers, RegistrationResult &result,
                       std::optional<decision::ScoredMotion> &corner_motion) {
  reset(result);
  if (guess) result.transform = *guess;
  std::string why;
  if (!params.validate(&why) || !checks.validate(&why))
    return fail(result, RegistrationStatus::kInvalidParameters, why);
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
  const bool verify_two = checks.two_inlier_min_overlap > 0.0 && params.refinement.enabled &&
                          params.ransac.model == TransformModel::kRigid && inlier_sources.size() == 2;
  if (!found.found || (inlier_sources.size() < min_inliers && !verify_two))
    return fail(result, RegistrationStatus::kTooFewInliers,
                "too few inliers: " + std::to_string(inlier_sources.size()) + " of " +
                    std::to_string(result.candidates.size()) + " pairs, need " + std::to_string(min_inliers));
  if (spread(inlier_sources) < checks.min_inlier_spread)
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
    decision::cornerHypotheses(coarse, found.rivals, params.refinement, starts);
    decision::Scorer scorer(source, target, params.free_space, buffers);
    decision::Judged judged =
        decision::chooseBest(decision::refineHypotheses(source, target, starts, buffers), guess, scorer);
    const RefinementResult &refined = judged.best.refined;
    result.contour_rmse = refined.rmse;
    result.overlap = refined.overlap;
    result.covariance = refined.covariance;
    const std::size_t corners = inlier_sources.size();
    // Three corners or more pin every direction; fewer leave it to the contours.
    result.degenerate = refined.degenerate && corners < 3;
    result.transform = refined.transform;
    // The contours must confirm what the corners agree on; a motion they do not confirm goes
    // back to the guess, and the contours' own hypotheses decide.
    std::string against;
    const RegistrationStatus verdict = decision::judgeCornerMotion(judged, corners, params, checks, guess,
                                                                   result.candidates, buffers, scorer, against);
    if (verdict != RegistrationStatus::kConverged) {
      scorer.score(judged.best);  // the fallback weighs it by its score
      corner_motion = judged.best;
      result.rejected = rejected(judged.best, scorer);
      if (verdict == RegistrationStatus::kAmbiguous) nameAlternatives(result, *result.rejected, judged, scorer);
      return failAtGuess(result, guess, verdict, std::to_string(corners) + " special points" + against);
    }
    if (judged.rival) result.rejected = rejected(*judged.rival, scorer);
    result.score = scorer.score(judged.best);
    if (result.degenerate) result.pinned = decision::pinnedPart(refined, checks.refinement_model);
  }
  result.converged = true;
  result.status = RegistrationStatus::kConverged;
  result.reason.clear();
}

// Few corners: the contours' own hypotheses, refined and judged. The corners' motion that the
// judge declined (`corner_motion`, refined and scored), if any, joins them when it is distinct from
// their best and scores clearly better (by more than the tie): the contours fit it best, so it
// is judged as a motion of the contours, which their own starts did not reach. One that scores
// no better than their best leaves the decision to them.
void tryLocalFallback(const ContourFeatures &source, const ContourFeatures &target, const RegistrationParams &params,
                      const decision::Checks &checks, const Eigen::Matrix3d *guess, RegistrationBuffers &buffers,
                      RegistrationResult &result, std::optional<decision::ScoredMotion> &corner_motion) {
  result.alternatives.clear();  // the fallback's verdict replaces the corners'
  const RefinementParams wide = decision::widened(params, checks);
  std::vector<RefinementStart> &starts = buffers.starts;
  decision::contourHypotheses(source, target, params, checks, guess, result.candidates, wide, starts);
  decision::Scorer scorer(source, target, params.free_space, buffers);
  const std::vector<RefinementResult> &hypotheses = decision::refineHypotheses(source, target, starts, buffers);
  decision::Judged judged = decision::chooseBest(hypotheses, guess, scorer);
  if (corner_motion &&
      motionDistance(corner_motion->refined.transform, judged.best.refined.transform) > kDistinctMotions &&
      corner_motion->score > scorer.score(judged.best) + decision::kScoreTie) {
    std::vector<RefinementResult> with_corners = hypotheses;
    with_corners.push_back(std::move(corner_motion->refined));
    judged = decision::chooseBest(with_corners, guess, scorer);
  }
  std::string why;
  const RegistrationStatus verdict = decision::judgeContourMotion(judged, params, checks, buffers, scorer, why);
  // The corner motion declined before, if any, is weighed with what the contours found.
  std::optional<RejectedMotion> declined = std::move(result.rejected);
  result.rejected.reset();
  if (verdict != RegistrationStatus::kConverged) {
    if (verdict == RegistrationStatus::kUnconstrained)
      result.pinned = decision::pinnedPart(judged.best.refined, checks.refinement_model);
    result.status = verdict;
    result.reason += "; " + why;
    const RejectedMotion best = rejected(judged.best, scorer);
    offerRejected(result, best);
    if (declined) offerRejected(result, *declined);
    if (verdict == RegistrationStatus::kAmbiguous) nameAlternatives(result, best, judged, scorer);
    return;
  }
  const RefinementResult &refined = judged.best.refined;
  if (judged.rival) offerRejected(result, rejected(*judged.rival, scorer));
  if (declined && motionDistance(declined->transform, refined.transform) > kDistinctMotions)
    offerRejected(result, *declined);
  result.transform = refined.transform;
  result.contour_rmse = refined.rmse;
  result.overlap = refined.overlap;
  result.score = scorer.score(judged.best);
  result.covariance = refined.covariance;
  result.degenerate = false;
  result.from_local_fallback = true;
  result.converged = true;
  result.status = RegistrationStatus::kConverged;
  result.reason.clear();
}

}  // namespace

void decision::registerContoursWith(const ContourFeatures &source, const ContourFeatures &target,
                                    const RegistrationParams &params, const Checks &checks, std::mt19937 &rng,
                                    const Eigen::Matrix3d *guess, RegistrationBuffers &buffers,
                                    RegistrationResult &result) {
  buffers.refiner.setModel(checks.refinement_model);
  std::optional<decision::ScoredMotion> corner_motion;  // the corners' motion, if the judge declined it
  registerByCorners(source, target, params, checks, rng, guess, buffers, result, corner_motion);
  if (!result.converged && isUndecided(result.status) && params.local_fallback_min_overlap > 0.0 &&
      params.refinement.enabled && !source.contours.empty() && !target.contours.empty())
    tryLocalFallback(source, target, params, checks, guess, buffers, result, corner_motion);
}

RegistrationResult decision::registerContoursWith(const ContourFeatures &source, const ContourFeatures &target,
                                                  const RegistrationParams &params, const Checks &checks,
                                                  std::mt19937 &rng, const Eigen::Matrix3d *guess) {
  RegistrationBuffers buffers;
  RegistrationResult result;
  registerContoursWith(source, target, params, checks, rng, guess, buffers, result);
  return result;
}

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
  decision::registerContoursWith(source, target, params, decision::Checks{}, rng, guess, buffers, result);
}

}  // namespace contour_reg
