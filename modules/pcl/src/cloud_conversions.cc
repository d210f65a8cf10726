#include "contour_reg/cloud_conversions.h"

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
