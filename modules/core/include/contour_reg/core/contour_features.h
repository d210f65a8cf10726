#pragma once
/// @file contour_features.h
/// Stages A-C in one call: scan -> segments -> equalized contours -> corner
/// response -> special points. Every intermediate result is kept, so debug
/// images and tests can show what the algorithm saw.

#include <cstdint>
#include <string>
#include <vector>

#include "contour_reg/core/contour.h"
#include "contour_reg/core/equalization.h"
#include "contour_reg/core/laser_scan.h"
#include "contour_reg/core/matched_filter.h"
#include "contour_reg/core/special_points.h"

namespace contour_reg {

/// All settings of stages A-C, with defaults for typical indoor scans.
struct ContourParams {
  SegmentationParams segmentation;
  EqualizationParams equalization;
  CornerFilterParams corner_filter;
  SpecialPointParams special_points;

  bool validate(std::string *why = nullptr) const;
};

/// What stages A-C produced for one scan.
struct ContourFeatures {
  std::vector<ContourSegment> segments;      ///< stage A
  std::vector<EqualizedContour> contours;    ///< stage B, one per segment
  std::vector<CornerResponse> responses;     ///< stage C, one per contour
  std::vector<SpecialPoint> special_points;  ///< stage C, all contours
  /// Every return stage A could use, isolated ones too (sensor frame): what the scan saw,
  /// for the beam-by-beam free-space evidence (free_space.h).
  ComplexSequence returns;
  /// A number unique to the extractContourFeatures call that filled these features (0 for
  /// features made any other way): registration keeps its target-side work under it.
  std::uint64_t extraction = 0;

  /// Buffers kept between scans: extracting a scan's features into an object that held an
  /// earlier scan's reuses them, and allocates nothing once they have grown large enough
  /// (odometry alternates two such objects).
  struct Buffers {
    SpareElements<ContourSegment> segments;
    SpareElements<EqualizedContour> contours;
    SpareElements<CornerResponse> responses;
    SpareElements<SpecialPoint> special_points;
    CornerBank bank;
    std::vector<double> arc;
    ComplexSequence polar_code;  ///< the scan's polar code, for callers that start from a scan or cloud
  } buffers;

  /// Empties the features, keeping their buffers.
  void clear();
};

/// Runs stages A-C on a polar code (points in the sensor frame, beam order, NaN where invalid).
/// Invalid parameters are the caller's to check with ContourParams::validate().
void extractContourFeatures(const ComplexSequence &polar_code, const ContourParams &params, ContourFeatures &features);

/// Convenience overload returning the features.
ContourFeatures extractContourFeatures(const ComplexSequence &polar_code, const ContourParams &params);

/// Runs stages A-C on a LaserScan; the scan's own range limits tighten the segmentation's.
ContourFeatures extractContourFeatures(const LaserScan &scan, const ContourParams &params);

/// The same into `features`, reusing its buffers.
void extractContourFeatures(const LaserScan &scan, const ContourParams &params, ContourFeatures &features);

}  // namespace contour_reg
