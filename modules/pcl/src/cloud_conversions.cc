#include "contour_reg/cloud_conversions.h"

namespace contour_reg {

bool isInBearingOrder(const ComplexSequence &points) {
  int wraps = 0;
  double previous = points.empty() ? 0.0 : std::arg(points.front());
  for (std::size_t n = 1; n < points.size(); ++n) {
    const double current = std::arg(points[n]);
    const double step = current - previous;
    previous = current;
    if (step >= 0.0) continue;
    if (step < -M_PI && ++wraps <= 1) continue;  // crossed +-pi going counter-clockwise
    return false;
  }
  return true;
}

void sortByBearing(ComplexSequence &points) {
  std::stable_sort(points.begin(), points.end(),
                   [](const Complex &a, const Complex &b) { return std::arg(a) < std::arg(b); });
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
  const std::size_t elements =
      std::min<std::size_t>(point.fragment.size(), ContourCorner::kFragmentElements);
  // Centre the fragment so that the vertex sits in the middle of the fixed-length field.
  const std::size_t offset = (ContourCorner::kFragmentElements - elements) / 2;
  for (std::size_t m = 0; m < elements; ++m) {
    out.fragment[2 * (offset + m)] = static_cast<float>(point.fragment[m].real());
    out.fragment[2 * (offset + m) + 1] = static_cast<float>(point.fragment[m].imag());
  }
  return out;
}

}  // namespace contour_reg
