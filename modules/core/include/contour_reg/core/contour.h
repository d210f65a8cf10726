#pragma once
/// @file contour.h
/// Stage A of the pipeline: a scan becomes contour segments.
///
/// The polar code (paper eq. 1) puts each beam's end point in the plane,
/// C(n) = r(n) cos a(n) + i r(n) sin a(n); the differential code (eq. 2) is the
/// sequence of elementary vectors y(n) = C(n+1) - C(n). The paper treats the
/// whole scan as one contour; on real scans an elementary vector must not join
/// two beams across an invalid reading or across an occluding edge, so the scan
/// is split into segments there, and segments too short to carry a feature are
/// dropped.

#include <string>
#include <vector>

#include "contour_reg/core/laser_scan.h"
#include "contour_reg/core/spare_elements.h"
#include "contour_reg/core/types.h"

namespace contour_reg {

/// How a polar code is cut into contour segments.
struct SegmentationParams {
  double range_min = 0.0;           ///< m, points closer to the sensor are invalid
  double range_max = 0.0;           ///< m, points at or beyond are invalid (0: no limit)
  double max_gap = 0.25;            ///< m, a jump longer than max_gap + max_gap_ratio * range splits
  double max_gap_ratio = 0.10;      ///< relative part of the jump threshold (grazing walls)
  int min_segment_points = 3;       ///< segments with fewer points are dropped
  double min_segment_length = 0.1;  ///< m, segments shorter than this are dropped

  /// True when the values make sense; `why` names the first bad one.
  bool validate(std::string *why = nullptr) const;
};

/// A run of consecutive valid beams with no jump between neighbours.
struct ContourSegment {
  ComplexSequence points;         ///< polar code of the run, in beam order
  std::vector<int> beam_indices;  ///< index in the scan of each point
};

/// Polar code of a scan, eq. (1). Invalid beams give NaN points, so beam indices stay aligned.
ComplexSequence polarCode(const LaserScan &scan);

/// The same into `code`, reusing its buffer.
void polarCode(const LaserScan &scan, ComplexSequence &code);

/// Differential code of a point sequence, eq. (2): y(n) = C(n+1) - C(n).
ComplexSequence differentialCode(const ComplexSequence &points);

/// Length of the polyline through `points`: the sum of |y(n)|.
double polylineLength(const ComplexSequence &points);

/// Splits a polar code (points in the sensor frame, in beam order, NaN where invalid)
/// into segments at invalid points and range jumps, and drops short segments.
std::vector<ContourSegment> splitIntoSegments(const ComplexSequence &polar_code, const SegmentationParams &params);

/// The same into `segments`, whose elements' buffers (and those kept in `spare`) are reused.
void splitIntoSegments(const ComplexSequence &polar_code, const SegmentationParams &params,
                       std::vector<ContourSegment> &segments, SpareElements<ContourSegment> &spare);

/// The points of a polar code that the segmentation may use (finite, within its range limits),
/// isolated returns included, into `returns`: what the scan saw.
void usableReturns(const ComplexSequence &polar_code, const SegmentationParams &params, ComplexSequence &returns);

}  // namespace contour_reg
