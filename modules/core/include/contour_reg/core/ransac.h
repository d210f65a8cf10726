#pragma once
/// @file ransac.h
/// Stage F: RANSAC over candidate pairs (paper section II-F and steps 1-6 of section III).
///
/// Repeat up to k times: draw a minimal sample of pairs (2 for the rigid model, 3 for
/// the paper's affine one), fit the model, count the pairs with |H p - q| < t as inliers
/// ("good"), keep the hypothesis with the most inliers (ties: the lower error), stop
/// early once the chance of having missed a better sample falls below 1 - confidence.
/// Then refit on all inliers and recount. When pairs carry their own rotation
/// (arg (N, G) of eq. 14), a sample whose pairs disagree with the rotation of its
/// hypothesis by more than kMaxRotationDisagreement is rejected before counting; an affine
/// hypothesis that stretches or shears beyond kMaxAffineDistortion is rejected too. The
/// caller owns the random generator.

#include <random>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "contour_reg/core/transform_estimation.h"

namespace contour_reg {

enum class TransformModel {
  kRigid,   ///< SE(2): rotation and translation, 2 pairs per sample
  kAffine,  ///< the paper's 6-parameter affine map, 3 pairs per sample
};

struct RansacParams {
  TransformModel model = TransformModel::kRigid;
  double inlier_threshold = 0.15;  ///< t, m
  int max_iterations = 300;        ///< k
  double confidence = 0.999;       ///< early stop

  bool validate(std::string *why = nullptr) const;
};

/// rad (15 deg): a sample's pairs must each turn their fragment (arg (N, G)) within this of
/// the hypothesis's rotation. A fragment's rotation is good to a few degrees; two pairs placed
/// crosswise imply a rotation that no pair of theirs agrees with.
constexpr double kMaxRotationDisagreement = 0.26;
/// Affine: hypotheses whose linear part scales any direction by more than this fraction away
/// from 1 are rejected (a LIDAR measures in metres; 3 pairs always fit some affine map).
constexpr double kMaxAffineDistortion = 0.15;

struct RansacResult {
  bool found = false;
  Eigen::Matrix3d transform = Eigen::Matrix3d::Identity();
  std::vector<int> inliers;  ///< indices of the inlier pairs
  double rmse = 0.0;         ///< m, of the inliers under `transform`
  int iterations = 0;
  /// Other hypotheses with as many inliers as the best that place the source elsewhere
  /// (a symmetric scene: two corners matched crosswise). The caller decides between them.
  std::vector<Eigen::Matrix3d> rivals;
};

/// Runs RANSAC on pairs (source[i], target[i]). `pair_rotations` may be empty.
RansacResult ransac(const Points2D &source, const Points2D &target, const std::vector<double> &pair_rotations,
                    const RansacParams &params, std::mt19937 &rng);

/// Working memory of ransac, kept between calls.
struct RansacScratch {
  std::vector<int> sample;
  Points2D sample_source, sample_target, inlier_source, inlier_target;
};

/// The same into `result`; `result` and `scratch` keep their buffers between calls, so that
/// nothing is allocated once they are large enough.
void ransac(const Points2D &source, const Points2D &target, const std::vector<double> &pair_rotations,
            const RansacParams &params, std::mt19937 &rng, RansacResult &result, RansacScratch &scratch);

}  // namespace contour_reg
