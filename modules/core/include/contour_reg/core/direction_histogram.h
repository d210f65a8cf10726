#pragma once
/// @file direction_histogram.h
/// Beyond the paper: motion hypotheses that need neither corners nor a guess.
///
/// After equalization (eqs. 3-11) every elementary vector has the same length, so a
/// histogram of their directions weighs each stretch of contour by its length: the angle
/// histogram of Weiss and von Puttkamer's scan matching, read straight off the
/// differential code. Indoors it has sharp peaks at the walls' directions.
///
/// 1. Rotation: peaks of the circular cross-correlation of the source and target angle
///    histograms; a turn of the robot shifts its histogram.
/// 2. Translation, for each rotation: along the normals of the target's two dominant,
///    non-parallel wall directions, peaks of the cross-correlation of the contour
///    vertices' projections (walls across a normal pile up in one bin).
/// Each rotation with each pair of offsets is one hypothesis, for the contour refinement
/// to test. A corridor has one wall direction: its hypotheses leave the motion along the
/// corridor at the guess, and the refinement then reports that direction unconstrained.

#include <string>
#include <vector>

#include <Eigen/Core>

#include "contour_reg/core/contour_features.h"

namespace contour_reg {

struct DirectionHistogramParams {
  int chord_elements = 4;        ///< the direction of a vertex is that of the chord this many elements long
  int angle_bins = 360;          ///< over the full turn
  double angle_smoothing = 2.0;  ///< bins, Gaussian sigma
  int rotations = 3;             ///< rotation peaks tried
  double offset_bin = 0.1;       ///< m
  double max_offset = 3.0;       ///< m, largest translation along a wall normal considered
  int offsets = 2;               ///< offset peaks tried per direction
  /// The second wall direction must differ from the first by at least this (rad).
  double min_direction_separation = 0.52;

  bool validate(std::string *why = nullptr) const;
};

/// Circular histogram of the chord directions of the equalized contours, `angle_bins`
/// bins from -pi, Gaussian-smoothed; counts are chords, i.e. contour length.
std::vector<double> angleHistogram(const std::vector<EqualizedContour> &contours,
                                   const DirectionHistogramParams &params);

/// Source-to-target motions suggested by the contours' directions and wall offsets, best
/// correlated first. `guess` (identity when null) fills directions the walls leave open.
std::vector<Eigen::Matrix3d> directionHypotheses(const ContourFeatures &source, const ContourFeatures &target,
                                                 const DirectionHistogramParams &params,
                                                 const Eigen::Matrix3d *guess = nullptr);

}  // namespace contour_reg
