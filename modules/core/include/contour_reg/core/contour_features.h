#pragma once
/// @file contour_features.h
/// Stages A-C in one call: scan -> segments -> equalized contours -> corner
/// response -> special points. Every intermediate result is kept, so debug
/// images and tests can show what the algorithm saw.

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
  std::vector<ContourSegment> segments;     ///< stage A
  std::vector<EqualizedContour> contours;   ///< stage B, one per segment
  std::vector<CornerResponse> responses;    ///< stage C, one per contour
  std::vector<SpecialPoint> special_points; ///< stage C, all contours

  void clear();
};

/// Runs stages A-C on a polar code (points in the sensor frame, beam order, NaN where invalid).
/// Invalid parameters are the caller's to check with ContourParams::validate().
void extractContourFeatures(const ComplexSequence &polar_code, const ContourParams &params,
                            ContourFeatures &features);

/// Convenience overload returning the features.
ContourFeatures extractContourFeatures(const ComplexSequence &polar_code, const ContourParams &params);

/// Runs stages A-C on a LaserScan; the scan's own range limits tighten the segmentation's.
ContourFeatures extractContourFeatures(const LaserScan &scan, const ContourParams &params);

}  // namespace contour_reg
