#include "contour_reg/core/registration.h"

#include <algorithm>
#include <cmath>

namespace contour_reg {

namespace {

RegistrationResult &fail(RegistrationResult &result, RegistrationStatus status, std::string reason) {
  result.converged = false;
  result.status = status;
  result.reason = std::move(reason);
  return result;
}

// Pairs consistent with the guess: target near the guessed source position, rotation near its yaw.
std::vector<Correspondence> gateByGuess(const std::vector<Correspondence> &pairs, const std::vector<SpecialPoint> &source,
                                        const std::vector<SpecialPoint> &target, const Eigen::Matrix3d &guess,
                                        const RegistrationParams &params, bool check_rotation) {
  std::vector<Correspondence> kept;
  const double yaw = yawOf(guess);
  for (const Correspondence &c : pairs) {
    const Eigen::Vector2d predicted = guess.topLeftCorner<2, 2>() * source[c.source].position + guess.topRightCorner<2, 1>();
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
  if (!correspondence.validate(why) || !ransac.validate(why) || !refinement.validate(why)) return false;
  if (min_special_points < 2 || min_inliers < 2) {
    if (why) *why = "min_special_points and min_inliers must be >= 2";
    return false;
  }
  return true;
}

const char *toString(RegistrationStatus status) {
  switch (status) {
    case RegistrationStatus::kConverged: return "converged";
    case RegistrationStatus::kInvalidParameters: return "invalid_parameters";
    case RegistrationStatus::kTooFewSpecialPoints: return "too_few_special_points";
    case RegistrationStatus::kTooFewCorrespondences: return "too_few_correspondences";
    case RegistrationStatus::kTooFewInliers: return "too_few_inliers";
    case RegistrationStatus::kDegenerate: return "degenerate";
  }
  return "unknown";
}

namespace {

// Stages D-F and the refinement, from the corners.
// RANSAC may end with rival motions as well supported as its best (a symmetric room seen
// from two corners matched crosswise). Each is refined on the contours; the best overlap
// wins, and where overlaps tie the motion nearest the guess (no motion without one) wins.
RefinementResult refineBest(const ContourFeatures &source, const ContourFeatures &target, const Eigen::Matrix3d &coarse,
                            const std::vector<Eigen::Matrix3d> &rivals, const RegistrationParams &params,
                            const Eigen::Matrix3d *guess) {
  const ContourRefiner refiner(target, params.refinement);
  RefinementResult best = refiner.refine(source, coarse);
  if (rivals.empty()) return best;
  const Eigen::Matrix3d prior = guess ? rigidPart(*guess) : Eigen::Matrix3d::Identity();
  auto distance = [&prior](const Eigen::Matrix3d &t) {  // m, with 1 m per rad of turn
    return (t.topRightCorner<2, 1>() - prior.topRightCorner<2, 1>()).norm() +
           std::abs(std::remainder(yawOf(t) - yawOf(prior), 2.0 * M_PI));
  };
  constexpr double kOverlapTie = 0.05;
  for (const Eigen::Matrix3d &rival : rivals) {
    const RefinementResult refined = refiner.refine(source, rigidPart(rival));
    const bool better = refined.overlap > best.overlap + kOverlapTie ||
                        (refined.overlap > best.overlap - kOverlapTie && distance(refined.transform) < distance(best.transform));
    if (better) best = refined;
  }
  return best;
}

RegistrationResult registerByCorners(const ContourFeatures &source, const ContourFeatures &target,
                                     const RegistrationParams &params, std::mt19937 &rng, const Eigen::Matrix3d *guess) {
  RegistrationResult result;
  if (guess) result.transform = *guess;
  std::string why;
  if (!params.validate(&why)) return fail(result, RegistrationStatus::kInvalidParameters, why);
  const auto &src = source.special_points, &dst = target.special_points;
  result.source_points = src.size();
  result.target_points = dst.size();
  const std::size_t needed = static_cast<std::size_t>(params.min_special_points);
  if (src.size() < needed || dst.size() < needed)
    return fail(result, RegistrationStatus::kTooFewSpecialPoints,
                "too few special points: " + std::to_string(src.size()) + " in source, " +
                    std::to_string(dst.size()) + " in target, need " + std::to_string(needed));

  // Stage D: candidate pairs by fragment distance (eq. 14).
  const bool invariant = params.correspondence.distance == FragmentDistance::kModulus;
  if (!invariant && guess) {
    std::vector<SpecialPoint> turned = src;  // pre-rotate by the guess for the Re form
    const Complex rotation = std::polar(1.0, yawOf(*guess));
    for (SpecialPoint &point : turned)
      for (Complex &v : point.fragment) v *= rotation;
    result.candidates = findCorrespondences(turned, dst, params.correspondence);
  } else {
    result.candidates = findCorrespondences(src, dst, params.correspondence);
  }
  if (guess && params.guess_max_distance > 0.0)
    result.candidates = gateByGuess(result.candidates, src, dst, *guess, params, invariant);
  const std::size_t sample = params.ransac.model == TransformModel::kRigid ? 2 : 3;
  if (result.candidates.size() < sample)
    return fail(result, RegistrationStatus::kTooFewCorrespondences,
                "too few candidate pairs: " + std::to_string(result.candidates.size()));

  // Stages E-F: RANSAC over the pairs.
  Points2D p, q;
  std::vector<double> rotations;
  for (const Correspondence &c : result.candidates) {
    p.push_back(src[c.source].position);
    q.push_back(dst[c.target].position);
    rotations.push_back(c.rotation);
  }
  const RansacResult found = ransac(p, q, rotations, params.ransac, rng);
  result.ransac_iterations = found.iterations;
  result.inliers = found.inliers;
  result.inlier_rmse = found.rmse;
  // Count distinct special points: one corner paired twice is no extra support.
  Points2D inlier_sources;
  for (int i : found.inliers)
    if (std::none_of(inlier_sources.begin(), inlier_sources.end(), [&](const Eigen::Vector2d &x) { return (x - p[i]).norm() < 1e-9; }))
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
    const RefinementResult refined = refineBest(source, target, coarse, found.rivals, params, guess);
    result.contour_rmse = refined.rmse;
    result.overlap = refined.overlap;
    result.covariance = refined.covariance;
    // Three corners or more pin every direction; fewer leave it to the contours.
    result.degenerate = refined.degenerate && inlier_sources.size() < 3;
    result.transform = refined.transform;
    if (verify_two && refined.overlap < params.two_inlier_min_overlap) {
      result.transform = guess ? *guess : Eigen::Matrix3d::Identity();
      return fail(result, RegistrationStatus::kTooFewInliers,
                  "too few inliers: 2 special points, and the contours overlap only " +
                      std::to_string(static_cast<int>(100 * refined.overlap)) + " % after alignment");
    }
  }
  result.converged = true;
  result.status = RegistrationStatus::kConverged;
  result.reason.clear();
  return result;
}

// Few corners: the guess, or a motion one pair of corners implies, refined on the contours
// and kept when well supported.
constexpr std::size_t kMaxPairHypotheses = 8;
void tryLocalFallback(const ContourFeatures &source, const ContourFeatures &target, const RegistrationParams &params,
                      const Eigen::Matrix3d *guess, RegistrationResult &result) {
  const Eigen::Matrix3d start = guess ? rigidPart(*guess) : Eigen::Matrix3d::Identity();
  // Besides the guess, each candidate pair of corners is a full hypothesis on its own: the
  // rotation arg (N, G) of eq. (14) and the translation that brings the two corners together.
  std::vector<Eigen::Matrix3d> hypotheses;
  if (params.correspondence.distance == FragmentDistance::kModulus) {
    const std::vector<Correspondence> pairs =
        result.candidates.empty() ? findCorrespondences(source.special_points, target.special_points, params.correspondence)
                                  : result.candidates;
    for (const Correspondence &c : pairs) {
      if (hypotheses.size() >= kMaxPairHypotheses) break;
      const Eigen::Matrix3d turn = rigidTransform(0.0, 0.0, c.rotation);
      const Eigen::Vector2d moved = target.special_points[c.target].position -
                                    turn.topLeftCorner<2, 2>() * source.special_points[c.source].position;
      hypotheses.push_back(rigidTransform(moved.x(), moved.y(), c.rotation));
    }
  }
  const RefinementResult refined = refineBest(source, target, start, hypotheses, params, guess);
  const bool weak = refined.degenerate || refined.constraint_ratio < params.local_fallback_min_constraint ||
                    refined.rotation_constraint_ratio < params.local_fallback_min_constraint;
  if (refined.overlap < params.local_fallback_min_overlap || weak) {
    result.reason += weak ? "; refining the guess on the contours leaves a direction weakly constrained (corridor, circle)"
                                        : "; refining the guess on the contours pairs only " +
                                              std::to_string(static_cast<int>(100 * refined.overlap)) + " %";
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
  RegistrationResult result = registerByCorners(source, target, params, rng, guess);
  const bool corners_undecided = result.status == RegistrationStatus::kTooFewSpecialPoints ||
                                 result.status == RegistrationStatus::kTooFewCorrespondences ||
                                 result.status == RegistrationStatus::kTooFewInliers;
  if (!result.converged && corners_undecided && params.local_fallback_min_overlap > 0.0 && params.refinement.enabled &&
      !source.contours.empty() && !target.contours.empty())
    tryLocalFallback(source, target, params, guess, result);
  return result;
}

}  // namespace contour_reg
