#include "contour_reg/cloud_conversions.h"

#include <iterator>
#include <limits>

namespace contour_reg {

bool isInBearingOrder(const ComplexSequence &points) {
  // Bearings increase from one point to the next when each turns counter-clockwise from the
  // one before (a cross product, no arc tangent), and they wrap around at most once: they
  // cross the negative x axis, from above to below, at most once.
  int wraps = 0;
  for (std::size_t n = 1; n < points.size(); ++n) {
    const Complex &a = points[n - 1], &b = points[n];
    if (a.real() * b.imag() - a.imag() * b.real() < 0.0) return false;
    const bool crosses_cut = a.imag() >= 0.0 && b.imag() < 0.0;
    if (crosses_cut && ++wraps > 1) return false;
  }
  return true;
}

void sortByBearing(ComplexSequence &points, std::vector<int> *order) {
  std::vector<std::size_t> by_bearing(points.size());
  std::iota(by_bearing.begin(), by_bearing.end(), std::size_t{0});
  std::vector<double> bearings(points.size());
  for (std::size_t n = 0; n < points.size(); ++n) bearings[n] = std::arg(points[n]);
  std::stable_sort(by_bearing.begin(), by_bearing.end(),
                   [&](std::size_t a, std::size_t b) { return bearings[a] < bearings[b]; });
  const ComplexSequence unsorted = points;
  const std::vector<int> positions = order ? *order : std::vector<int>{};
  for (std::size_t n = 0; n < points.size(); ++n) {
    points[n] = unsorted[by_bearing[n]];
    if (order) (*order)[n] = positions[by_bearing[n]];
  }
}

ContourCorner toContourCorner(const SpecialPoint &point) {
  ContourCorner out{};
  out.x = static_cast<float>(point.position.x());
  out.y = static_cast<float>(point.position.y());
  out.z = 0.0f;
  out.data[3] = 1.0f;
  out.corner_angle = static_cast<float>(point.corner_angle);
  out.orientation = static_cast<float>(point.orientation);
  out.response = static_cast<float>(point.response);
  out.turn = static_cast<float>(point.turn);
  const std::size_t elements = std::min<std::size_t>(point.fragment.size(), ContourCorner::kFragmentElements);
  // Centre the fragment so that the vertex sits in the middle of the fixed-length field.
  const std::size_t offset = (ContourCorner::kFragmentElements - elements) / 2;
  for (std::size_t m = 0; m < elements; ++m) {
    out.fragment[2 * (offset + m)] = static_cast<float>(point.fragment[m].real());
    out.fragment[2 * (offset + m) + 1] = static_cast<float>(point.fragment[m].imag());
  }
  return out;
}

ContourCorner noContourCorner() {
  ContourCorner out{};
  const float nan = std::numeric_limits<float>::quiet_NaN();
  out.x = out.y = out.z = nan;
  out.data[3] = 1.0f;
  out.corner_angle = out.orientation = out.response = out.turn = nan;
  std::fill(std::begin(out.fragment), std::end(out.fragment), nan);
  return out;
}

int nearestBeam(const ContourFeatures &features, const SpecialPoint &point) {
  if (point.contour < 0 || point.contour >= static_cast<int>(features.segments.size())) return -1;
  const ContourSegment &segment = features.segments[static_cast<std::size_t>(point.contour)];
  const Complex vertex(point.position.x(), point.position.y());
  int best = -1;
  double best_distance = std::numeric_limits<double>::infinity();
  for (std::size_t n = 0; n < segment.points.size(); ++n) {
    const double distance = squaredMagnitude(segment.points[n] - vertex);
    if (distance < best_distance) {
      best_distance = distance;
      best = segment.beam_indices[n];
    }
  }
  return best;
}

}  // namespace contour_reg
