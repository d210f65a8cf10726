#include "contour_reg/core/ransac.h"
#include "validation.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/LU>
#include <Eigen/SVD>

namespace contour_reg {

namespace {

double angleDifference(double a, double b) { return std::abs(std::remainder(a - b, 2.0 * M_PI)); }

// Fits the model; an affine map must stay close to a rigid one.
bool fit(const RansacParams &params, const Points2D &source, const Points2D &target, Eigen::Matrix3d &transform) {
  if (params.model == TransformModel::kRigid) return estimateRigid(source, target, transform);
  if (!estimateAffine(source, target, transform)) return false;
  const Eigen::JacobiSVD<Eigen::Matrix2d> svd(transform.topLeftCorner<2, 2>());
  const Eigen::Vector2d scales = svd.singularValues();
  return transform.topLeftCorner<2, 2>().determinant() > 0.0 && std::abs(scales(0) - 1.0) <= kMaxAffineDistortion &&
         std::abs(scales(1) - 1.0) <= kMaxAffineDistortion;
}

// How many pairs `transform` takes within t of their target (|H p - q| < t), and the sum of
// their squared errors.
std::size_t countInliers(const Eigen::Matrix3d &transform, const Points2D &source, const Points2D &target,
                         double threshold, double &squared_error) {
  std::size_t count = 0;
  squared_error = 0.0;
  const double t2 = threshold * threshold;
  for (std::size_t i = 0; i < source.size(); ++i) {
    const double e2 = (transformPoint(transform, source[i]) - target[i]).squaredNorm();
    if (e2 < t2) {
      ++count;
      squared_error += e2;
    }
  }
  return count;
}

// The inliers themselves, into `inliers`; returns the sum of their squared errors.
double listInliers(const Eigen::Matrix3d &transform, const Points2D &source, const Points2D &target, double threshold,
                   std::vector<int> &inliers) {
  inliers.clear();
  double squared_error = 0.0;
  const double t2 = threshold * threshold;
  for (std::size_t i = 0; i < source.size(); ++i) {
    const double e2 = (transformPoint(transform, source[i]) - target[i]).squaredNorm();
    if (e2 < t2) {
      inliers.push_back(static_cast<int>(i));
      squared_error += e2;
    }
  }
  return squared_error;
}

// Draws `size` distinct indices below n.
void drawSample(std::size_t n, std::size_t size, std::mt19937 &rng, std::vector<int> &sample) {
  std::uniform_int_distribution<std::size_t> pick(0, n - 1);
  sample.clear();
  while (sample.size() < size) {
    const int i = static_cast<int>(pick(rng));
    if (std::find(sample.begin(), sample.end(), i) == sample.end()) sample.push_back(i);
  }
}

}  // namespace

bool RansacParams::validate(std::string *why) const {
  if (!(inlier_threshold > 0.0)) return invalid(why, "ransac.inlier_threshold must be > 0");
  if (max_iterations < 1) return invalid(why, "ransac.max_iterations must be >= 1");
  if (!(confidence > 0.0 && confidence < 1.0)) return invalid(why, "ransac.confidence must lie in (0, 1)");
  return true;
}

namespace {

constexpr std::size_t kMaxRivals = 4;

// Two motions that place the source within 0.3 m and 10 deg of each other.
bool sameMotion(const Eigen::Matrix3d &a, const Eigen::Matrix3d &b) {
  return (a.topRightCorner<2, 1>() - b.topRightCorner<2, 1>()).norm() < 0.3 &&
         angleDifference(yawOf(rigidPart(a)), yawOf(rigidPart(b))) < 10.0 * M_PI / 180.0;
}

}  // namespace

RansacResult ransac(const Points2D &source, const Points2D &target, const std::vector<double> &pair_rotations,
                    const RansacParams &params, std::mt19937 &rng) {
  RansacResult result;
  RansacScratch scratch;
  ransac(source, target, pair_rotations, params, rng, result, scratch);
  return result;
}

void ransac(const Points2D &source, const Points2D &target, const std::vector<double> &pair_rotations,
            const RansacParams &params, std::mt19937 &rng, RansacResult &result, RansacScratch &scratch) {
  result.found = false;
  result.transform.setIdentity();
  result.inliers.clear();
  result.rmse = 0.0;
  result.iterations = 0;
  result.rivals.clear();
  const std::size_t sample_size = params.model == TransformModel::kRigid ? 2 : 3;
  const std::size_t n = source.size();
  if (n < sample_size || target.size() != n) return;
  const bool check_rotations = pair_rotations.size() == n;

  std::size_t best_count = 0;
  double best_error = std::numeric_limits<double>::infinity();
  double needed_iterations = params.max_iterations;
  std::vector<int> &sample = scratch.sample;
  Points2D &sample_source = scratch.sample_source, &sample_target = scratch.sample_target;
  sample_source.resize(sample_size);
  sample_target.resize(sample_size);
  for (int iteration = 0; iteration < params.max_iterations && iteration < needed_iterations; ++iteration) {
    result.iterations = iteration + 1;
    drawSample(n, sample_size, rng, sample);  // step 2: a "trial" set of pairs
    for (std::size_t k = 0; k < sample_size; ++k) {
      sample_source[k] = source[sample[k]];
      sample_target[k] = target[sample[k]];
    }
    Eigen::Matrix3d hypothesis;
    if (!fit(params, sample_source, sample_target, hypothesis)) continue;  // step 3
    if (check_rotations) {
      const double yaw = yawOf(rigidPart(hypothesis));
      bool agree = true;
      for (int i : sample) agree = agree && angleDifference(pair_rotations[i], yaw) <= kMaxRotationDisagreement;
      if (!agree) continue;
    }
    double error = 0.0;
    const std::size_t inliers = countInliers(hypothesis, source, target, params.inlier_threshold, error);  // step 4
    if (result.found && inliers == best_count && !sameMotion(hypothesis, result.transform)) {
      const bool known = std::any_of(result.rivals.begin(), result.rivals.end(),
                                     [&](const Eigen::Matrix3d &r) { return sameMotion(r, hypothesis); });
      if (!known && result.rivals.size() < kMaxRivals) result.rivals.push_back(hypothesis);
    }
    if (inliers > best_count || (inliers == best_count && error < best_error)) {  // step 5
      if (inliers > best_count)
        result.rivals.clear();
      else if (result.found && !sameMotion(hypothesis, result.transform)) {
        result.rivals.erase(std::remove_if(result.rivals.begin(), result.rivals.end(),
                                           [&](const Eigen::Matrix3d &r) { return sameMotion(r, hypothesis); }),
                            result.rivals.end());
        result.rivals.push_back(result.transform);
      }
      best_count = inliers;
      best_error = error;
      result.transform = hypothesis;
      result.found = true;
      const double ratio = static_cast<double>(best_count) / static_cast<double>(n);
      const double p_good = std::pow(ratio, static_cast<double>(sample_size));
      if (p_good >= 1.0) break;
      needed_iterations = std::log(1.0 - params.confidence) / std::log(1.0 - std::max(p_good, 1e-12));
    }
  }
  if (!result.found) return;

  // Refit on all inliers, recount, and keep the refit when it does not lose inliers.
  double error = listInliers(result.transform, source, target, params.inlier_threshold, result.inliers);
  Points2D &in_source = scratch.inlier_source, &in_target = scratch.inlier_target;
  for (int round = 0; round < 2; ++round) {
    in_source.clear();
    in_target.clear();
    for (int i : result.inliers) {
      in_source.push_back(source[i]);
      in_target.push_back(target[i]);
    }
    Eigen::Matrix3d refit;
    if (!fit(params, in_source, in_target, refit)) break;
    double refit_error = 0.0;
    if (countInliers(refit, source, target, params.inlier_threshold, refit_error) < result.inliers.size()) break;
    result.transform = refit;
    error = listInliers(result.transform, source, target, params.inlier_threshold, result.inliers);
  }
  result.rmse = result.inliers.empty() ? 0.0 : std::sqrt(error / static_cast<double>(result.inliers.size()));
}

}  // namespace contour_reg
