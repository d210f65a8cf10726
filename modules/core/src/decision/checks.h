#pragma once
/// @file checks.h
/// The judge's fixed thresholds: what a motion that few corners agree on must prove before it
/// stands, and where the contours' own hypotheses start; and the refinement's model.
///
/// They belong to the method, not to a scene: chosen on the three logs with Kümmerle relations,
/// checked on the twelve Radish logs and on simulated runs (docs/results.md), and the same for
/// every LIDAR the project was measured with. A user sets what the scans and the robot say
/// (RegistrationParams); tests and studies of the decision change these through
/// registerContoursWith, to show what each check decides.

#include <random>
#include <string>

#include <Eigen/Core>

#include "contour_reg/core/contour_features.h"
#include "contour_reg/core/refinement.h"
#include "contour_reg/core/registration.h"

namespace contour_reg::decision {

struct Checks {
  /// fraction: a motion two corners agree on stands when, refined, at least this much of the
  /// source contour lies on the target contour (0: two corners never suffice).
  double two_inlier_min_overlap = 0.6;
  /// fraction: a motion of three corners or more must put at least this much of the source
  /// contour on the target contour, or it goes to the local fallback: corners paired wrongly
  /// along cluttered or noisy walls can agree on a motion the contours refute (0: no check).
  double corner_min_overlap = 0.3;
  /// fraction of RegistrationParams::local_fallback_min_overlap: the contours' own motion with
  /// less overlap, but at least this share of it, stands when the beams of both scans agree with
  /// it (at most kScoreTie of their returns in the other scan's free space, beam by beam):
  /// views that share little, as in open halls, pair little contour at the right motion. 1: the
  /// overlap alone decides; free space off: the same.
  double beam_agreed_overlap_share = 0.75;
  /// m, the inlier special points must span at least this, or the motion is degenerate.
  double min_inlier_spread = 0.3;
  /// m, the refinement of the guess (identity without one) in the local fallback and in the
  /// check against the guess starts pairing points this far apart: the guess may be far off.
  double local_fallback_max_distance = 1.0;
  /// Whether the motions of the contours' direction and wall-offset histograms join the
  /// fallback's starts (directionHypotheses with the default DirectionHistogramParams).
  bool direction_hypotheses = true;
  /// special points: a motion the corners decide with at most this many inliers must pass the
  /// probe (RegistrationParams::probe_distance); three corners along one wall of a corridor fix
  /// its axis only as well as they are spread.
  int probe_max_inliers = 3;
  /// special points: a motion the corners decide with at most this many inliers must agree
  /// with the contours' refinement of the guess, or score clearly better (by more than
  /// kScoreTie); door corners every few metres can match one period off (0: no check).
  int guess_check_max_inliers = 5;
  /// How the refinement samples and weighs the contours and what its covariance counts (refinement.h).
  RefinementModel refinement_model;

  bool validate(std::string *why = nullptr) const;
};

/// registerContours (registration.h) with `checks` in place of the defaults.
void registerContoursWith(const ContourFeatures &source, const ContourFeatures &target,
                          const RegistrationParams &params, const Checks &checks, std::mt19937 &rng,
                          const Eigen::Matrix3d *guess, RegistrationBuffers &buffers, RegistrationResult &result);

/// The same, returning the result.
RegistrationResult registerContoursWith(const ContourFeatures &source, const ContourFeatures &target,
                                        const RegistrationParams &params, const Checks &checks, std::mt19937 &rng,
                                        const Eigen::Matrix3d *guess = nullptr);

}  // namespace contour_reg::decision
