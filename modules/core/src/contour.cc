#include "contour_reg/core/contour.h"
#include "validation.h"

#include <cmath>
#include <limits>

namespace contour_reg {

namespace {

bool isUsable(const Complex &point, const SegmentationParams &params) {
  if (!isFinite(point)) return false;
  const double range = magnitude(point);
  return range > 0.0 && range >= params.range_min && (params.range_max <= 0.0 || range < params.range_max);
}

bool isLongEnough(const ContourSegment &segment, const SegmentationParams &params) {
  return static_cast<int>(segment.points.size()) >= params.min_segment_points &&
         polylineLength(segment.points) >= params.min_segment_length;
}

}  // namespace

bool SegmentationParams::validate(std::string *why) const {
  if (!(range_min >= 0.0)) return invalid(why, "segmentation.range_min must be >= 0");
  if (!(range_max >= 0.0)) return invalid(why, "segmentation.range_max must be >= 0");
  if (!(max_gap > 0.0)) return invalid(why, "segmentation.max_gap must be > 0");
  if (!(max_gap_ratio >= 0.0)) return invalid(why, "segmentation.max_gap_ratio must be >= 0");
  if (min_segment_points < 2) return invalid(why, "segmentation.min_segment_points must be >= 2");
  if (!(min_segment_length >= 0.0)) return invalid(why, "segmentation.min_segment_length must be >= 0");
  return true;
}

// Eq. (1): C(n) = r(n) cos a(n) + i r(n) sin a(n).
ComplexSequence polarCode(const LaserScan &scan) {
  ComplexSequence code;
  polarCode(scan, code);
  return code;
}

void polarCode(const LaserScan &scan, ComplexSequence &code) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  code.resize(scan.ranges.size());
  // The beam direction turns by the same angle from beam to beam: one complex product per
  // beam instead of a sine and a cosine (the rounding this accumulates stays below 1e-12).
  Complex direction = std::polar(1.0, scan.angle_min);
  const Complex turn = std::polar(1.0, scan.angle_increment);
  for (std::size_t n = 0; n < scan.ranges.size(); ++n, direction *= turn) {
    const double r = scan.ranges[n];
    code[n] = scan.isValidRange(r) ? r * direction : Complex(nan, nan);
  }
}

// Eq. (2): y(n) = C(n+1) - C(n).
ComplexSequence differentialCode(const ComplexSequence &points) {
  ComplexSequence code;
  if (points.size() < 2) return code;
  code.reserve(points.size() - 1);
  for (std::size_t n = 0; n + 1 < points.size(); ++n) code.push_back(points[n + 1] - points[n]);
  return code;
}

double polylineLength(const ComplexSequence &points) {
  double length = 0.0;
  for (std::size_t n = 0; n + 1 < points.size(); ++n) length += magnitude(points[n + 1] - points[n]);
  return length;
}

std::vector<ContourSegment> splitIntoSegments(const ComplexSequence &polar_code, const SegmentationParams &params) {
  std::vector<ContourSegment> segments;
  SpareElements<ContourSegment> spare;
  splitIntoSegments(polar_code, params, segments, spare);
  return segments;
}

void splitIntoSegments(const ComplexSequence &polar_code, const SegmentationParams &params,
                       std::vector<ContourSegment> &segments, SpareElements<ContourSegment> &spare) {
  spare.clear(segments);
  // Whether neighbouring usable points are too far apart to lie on one surface.
  const auto breaks = [&](const Complex &previous, const Complex &point) {
    const double range = std::min(magnitude(point), magnitude(previous));
    return magnitude(point - previous) > params.max_gap + params.max_gap_ratio * range;
  };
  const std::size_t size = polar_code.size();
  for (std::size_t first = 0; first < size;) {
    if (!isUsable(polar_code[first], params)) {
      ++first;
      continue;
    }
    // The run of usable points without a gap that starts at `first`, copied at once.
    std::size_t end = first + 1;
    while (end < size && isUsable(polar_code[end], params) && !breaks(polar_code[end - 1], polar_code[end])) ++end;
    ContourSegment &segment = spare.append(segments);
    segment.points.assign(polar_code.begin() + static_cast<std::ptrdiff_t>(first),
                          polar_code.begin() + static_cast<std::ptrdiff_t>(end));
    segment.beam_indices.resize(end - first);
    for (std::size_t n = first; n < end; ++n) segment.beam_indices[n - first] = static_cast<int>(n);
    if (!isLongEnough(segment, params)) spare.dropLast(segments);
    first = end;
  }
}

void usableReturns(const ComplexSequence &polar_code, const SegmentationParams &params, ComplexSequence &returns) {
  returns.clear();
  returns.reserve(polar_code.size());
  for (const Complex &point : polar_code)
    if (isUsable(point, params)) returns.push_back(point);
}

}  // namespace contour_reg
