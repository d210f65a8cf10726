#include "contour_reg/core/equalization.h"
#include "validation.h"

#include <algorithm>
#include <cmath>

namespace contour_reg {

namespace {

// Resamples the polyline at arc lengths start, start + step, ..., start + count * step
// (eqs. 4-11: each new vertex ends a piece made of the rest of one raw vector, whole raw
// vectors, and the used part of the raw vector where the piece ends). `arc` is
// arcLengths(points).
void resample(const ComplexSequence &points, const std::vector<double> &arc, double start, double step,
              std::size_t count, EqualizedContour &contour) {
  contour.step = step;
  contour.vertices.clear();
  contour.spacing.clear();
  if (points.size() < 2 || count == 0 || !(step > 0.0)) return;
  contour.vertices.reserve(count + 1);
  contour.spacing.reserve(count + 1);
  std::size_t hint = 0;
  for (std::size_t r = 0; r <= count; ++r) {
    contour.vertices.push_back(pointAtArcLength(points, arc, start + static_cast<double>(r) * step, &hint));
    contour.spacing.push_back(arc[hint + 1] - arc[hint]);  // the raw vector the vertex lies on
  }
}

// The element length of every segment: the fixed step, or the paper's total length / p.
double elementStep(const std::vector<ContourSegment> &segments, const EqualizationParams &params) {
  if (params.mode == EqualizationMode::kFixedStep) return params.step;
  double total = 0.0;
  for (const auto &segment : segments) total += polylineLength(segment.points);
  return total / std::max(params.count, 1);
}

// The number of elements of a polyline `length` m long at a fixed step.
std::size_t elementCountAtStep(double length, double step) {
  // A tiny tolerance keeps a segment whose length is an exact multiple of the step whole.
  return static_cast<std::size_t>(std::floor(length / step + 1e-9));
}

}  // namespace

bool EqualizationParams::validate(std::string *why) const {
  if (mode == EqualizationMode::kFixedStep && !(step >= kLeastStep && step <= kLongestStep))
    return invalid(why, "equalization.step must be within 0.001-10 m");
  if (mode == EqualizationMode::kFixedCount && !(count >= 1 && count <= kMostElements))
    return invalid(why, "equalization.count must be within 1-100000");
  return true;
}

std::vector<double> arcLengths(const ComplexSequence &points) {
  std::vector<double> arc;
  arcLengths(points, arc);
  return arc;
}

void arcLengths(const ComplexSequence &points, std::vector<double> &arc) {
  arc.assign(points.size(), 0.0);
  for (std::size_t n = 1; n < points.size(); ++n) arc[n] = arc[n - 1] + magnitude(points[n] - points[n - 1]);
}

Complex pointAtArcLength(const ComplexSequence &points, const std::vector<double> &arc, double s, std::size_t *hint) {
  if (points.empty()) return {};
  if (s <= 0.0) return points.front();
  if (s >= arc.back()) return points.back();
  // The raw vector the point lies on: the first n with arc[n + 1] >= s (the raw vectors before
  // it are passed over whole, eq. 7), walked from a valid hint, else found by bisection.
  std::size_t n = hint ? *hint : 0;
  if (hint && n < points.size() - 1 && arc[n] <= s) {
    while (n + 2 < points.size() && arc[n + 1] < s) ++n;
  } else {
    n = static_cast<std::size_t>(std::lower_bound(arc.begin() + 1, arc.end() - 1, s) - (arc.begin() + 1));
  }
  if (hint) *hint = n;
  const double length = arc[n + 1] - arc[n];
  if (length <= 0.0) return points[n];
  const double used = (s - arc[n]) / length;  // used part of the raw vector (eqs. 8-9)
  return points[n] + used * (points[n + 1] - points[n]);
}

// Eq. (3): e = (1/p) * sum |y(n)|.
EqualizedContour equalizeByCount(const ComplexSequence &points, int count) {
  EqualizedContour contour;
  if (count < 1 || points.empty()) return contour;
  const std::vector<double> arc = arcLengths(points);
  resample(points, arc, 0.0, arc.back() / count, static_cast<std::size_t>(count), contour);
  return contour;
}

EqualizedContour equalizeByStep(const ComplexSequence &points, double step) {
  EqualizedContour contour;
  if (!(step > 0.0) || points.empty()) return contour;
  const std::vector<double> arc = arcLengths(points);
  resample(points, arc, 0.0, step, elementCountAtStep(arc.back(), step), contour);
  return contour;
}

void equalizeCentred(const ComplexSequence &points, double step, EqualizedContour &contour, std::vector<double> &arc) {
  arcLengths(points, arc);
  const double length = arc.empty() ? 0.0 : arc.back();
  const std::size_t count = step > 0.0 ? elementCountAtStep(length, step) : 0;
  resample(points, arc, std::max(0.0, 0.5 * (length - static_cast<double>(count) * step)), step, count, contour);
}

std::vector<EqualizedContour> equalizeSegments(const std::vector<ContourSegment> &segments,
                                               const EqualizationParams &params) {
  std::vector<EqualizedContour> contours;
  SpareElements<EqualizedContour> spare;
  std::vector<double> arc;
  equalizeSegments(segments, params, contours, spare, arc);
  return contours;
}

void equalizeSegments(const std::vector<ContourSegment> &segments, const EqualizationParams &params,
                      std::vector<EqualizedContour> &contours, SpareElements<EqualizedContour> &spare,
                      std::vector<double> &arc) {
  spare.resize(contours, segments.size());
  const double step = elementStep(segments, params);
  for (std::size_t k = 0; k < segments.size(); ++k) {
    const ComplexSequence &points = segments[k].points;
    EqualizedContour &contour = contours[k];
    contour.segment = static_cast<int>(k);
    arcLengths(points, arc);
    const double length = arc.empty() ? 0.0 : arc.back();
    if (params.mode == EqualizationMode::kFixedCount) {
      // Each segment gets a whole number of elements, near its share of the p.
      const long count = step > 0.0 ? std::max(1L, std::lround(length / step)) : 1L;
      resample(points, arc, 0.0, length / static_cast<double>(count), static_cast<std::size_t>(count), contour);
    } else {
      resample(points, arc, 0.0, step, step > 0.0 ? elementCountAtStep(length, step) : 0, contour);
    }
  }
}

}  // namespace contour_reg
