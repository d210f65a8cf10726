#include "contour_reg/core/equalization.h"
#include "contour_reg/core/validation.h"

#include <algorithm>
#include <cmath>

namespace contour_reg {

namespace {

// Resamples the polyline at arc lengths 0, step, ..., count * step (eqs. 4-11:
// each new vertex ends a piece made of the rest of one raw vector, whole raw
// vectors, and the used part of the raw vector where the piece ends).
EqualizedContour resample(const ComplexSequence &points, double step, std::size_t count) {
  EqualizedContour contour;
  contour.step = step;
  if (points.size() < 2 || count == 0 || !(step > 0.0)) return contour;
  const std::vector<double> arc = arcLengths(points);
  contour.vertices.reserve(count + 1);
  std::size_t hint = 0;
  for (std::size_t r = 0; r <= count; ++r)
    contour.vertices.push_back(pointAtArcLength(points, arc, static_cast<double>(r) * step, &hint));
  return contour;
}

}  // namespace

bool EqualizationParams::validate(std::string *why) const {
  if (mode == EqualizationMode::kFixedStep && !(step > 0.0))
    return invalid(why, "equalization.step must be > 0");
  if (mode == EqualizationMode::kFixedCount && count < 1)
    return invalid(why, "equalization.count must be >= 1");
  return true;
}

std::vector<double> arcLengths(const ComplexSequence &points) {
  std::vector<double> arc(points.size(), 0.0);
  for (std::size_t n = 1; n < points.size(); ++n) arc[n] = arc[n - 1] + magnitude(points[n] - points[n - 1]);
  return arc;
}

Complex pointAtArcLength(const ComplexSequence &points, const std::vector<double> &arc, double s,
                         std::size_t *hint) {
  if (points.empty()) return {};
  if (s <= 0.0) return points.front();
  if (s >= arc.back()) return points.back();
  std::size_t n = hint ? *hint : 0;
  if (n >= points.size() - 1 || arc[n] > s) n = 0;
  while (n + 2 < points.size() && arc[n + 1] < s) ++n;  // raw vectors passed over whole (eq. 7)
  if (hint) *hint = n;
  const double length = arc[n + 1] - arc[n];
  if (length <= 0.0) return points[n];
  const double used = (s - arc[n]) / length;  // used part of the raw vector (eqs. 8-9)
  return points[n] + used * (points[n + 1] - points[n]);
}

// Eq. (3): e = (1/p) * sum |y(n)|.
EqualizedContour equalizeByCount(const ComplexSequence &points, int count) {
  if (count < 1) return {};
  const double length = polylineLength(points);
  return resample(points, length / count, static_cast<std::size_t>(count));
}

EqualizedContour equalizeByStep(const ComplexSequence &points, double step) {
  if (!(step > 0.0)) return {};
  const double length = polylineLength(points);
  // A tiny tolerance keeps a segment whose length is an exact multiple of the step whole.
  const auto count = static_cast<std::size_t>(std::floor(length / step + 1e-9));
  return resample(points, step, count);
}

std::vector<EqualizedContour> equalizeSegments(const std::vector<ContourSegment> &segments,
                                               const EqualizationParams &params) {
  std::vector<EqualizedContour> contours;
  contours.reserve(segments.size());
  double step = params.step;
  if (params.mode == EqualizationMode::kFixedCount) {
    double total = 0.0;
    for (const auto &segment : segments) total += polylineLength(segment.points);
    step = total / std::max(params.count, 1);
  }
  for (std::size_t k = 0; k < segments.size(); ++k) {
    const ComplexSequence &points = segments[k].points;
    EqualizedContour contour;
    if (params.mode == EqualizationMode::kFixedCount) {
      const double length = polylineLength(points);
      const int count = std::max(1, static_cast<int>(std::lround(length / step)));
      contour = equalizeByCount(points, count);
    } else {
      contour = equalizeByStep(points, step);
    }
    contour.segment = static_cast<int>(k);
    contours.push_back(std::move(contour));
  }
  return contours;
}

}  // namespace contour_reg
