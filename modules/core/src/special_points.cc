#include "contour_reg/core/special_points.h"
#include "validation.h"

#include <algorithm>
#include <cmath>

namespace contour_reg {

namespace {

struct Line {
  Complex point;      // a point on the line (centroid of the fitted points)
  Complex direction;  // unit, oriented along the contour
  double rms = 0.0;   // root mean square distance of the fitted points from the line
};

// Total-least-squares line through the raw points whose arc length lies in [from, to].
bool fitLine(const ComplexSequence &points, const std::vector<double> &arc, double from, double to, Line &line) {
  // The arc lengths grow along the contour: the points within [from, to] are one run.
  const std::size_t first = std::lower_bound(arc.begin(), arc.end(), from) - arc.begin();
  const std::size_t end = std::upper_bound(arc.begin() + first, arc.end(), to) - arc.begin();
  if (end < first + 2) return false;
  const int count = static_cast<int>(end - first);
  Complex sum = 0.0;
  for (std::size_t n = first; n < end; ++n) sum += points[n];
  const Complex centroid = sum / static_cast<double>(count);
  double sxx = 0.0, syy = 0.0, sxy = 0.0;
  for (std::size_t n = first; n < end; ++n) {
    const Complex d = points[n] - centroid;
    sxx += d.real() * d.real();
    syy += d.imag() * d.imag();
    sxy += d.real() * d.imag();
  }
  const double angle = 0.5 * std::atan2(2.0 * sxy, sxx - syy);  // principal axis
  Complex direction = std::polar(1.0, angle);
  const Complex along = points[end - 1] - points[first];
  if ((along * std::conj(direction)).real() < 0.0) direction = -direction;
  // The smaller eigenvalue of the scatter matrix is the sum of squared distances from the line.
  const double mean = 0.5 * (sxx + syy), half_gap = std::hypot(0.5 * (sxx - syy), sxy);
  line = {centroid, direction, std::sqrt(std::max(0.0, mean - half_gap) / count)};
  return true;
}

// Fits the arm that runs from the vertex at arc length `at` in direction `sign` (-1 back,
// +1 ahead). The arm starts as the filter's s elements and grows while it stays straight,
// so long walls give precise directions.
bool fitArm(const ComplexSequence &points, const std::vector<double> &arc, double at, int sign, double margin,
            double reach, const SpecialPointParams &params, Line &arm) {
  auto fit = [&](double length, Line &line) {
    return sign < 0 ? fitLine(points, arc, at - length, at - margin, line)
                    : fitLine(points, arc, at + margin, at + length, line);
  };
  if (!fit(reach, arm)) return false;
  for (double length = 1.5 * reach; length <= params.max_arm_length; length *= 1.5) {
    Line longer;
    if (!fit(length, longer) || longer.rms > params.max_arm_rms) break;
    arm = longer;
  }
  return true;
}

// Intersection of two lines; false when they are close to parallel.
bool intersect(const Line &a, const Line &b, Complex &point) {
  const double cross = (std::conj(a.direction) * b.direction).imag();
  if (std::abs(cross) < std::sin(10.0 * M_PI / 180.0)) return false;
  const Complex d = b.point - a.point;
  const double t = (std::conj(d) * b.direction).imag() / cross;
  point = a.point + t * a.direction;
  return true;
}

// Offset of a parabola's peak through three samples, in (-0.5, 0.5).
double parabolicPeak(double left, double centre, double right) {
  const double curvature = left - 2.0 * centre + right;
  if (curvature >= 0.0) return 0.0;
  return std::clamp(0.5 * (left - right) / curvature, -0.5, 0.5);
}

bool isLocalMaximum(const std::vector<double> &c, std::size_t n, int radius) {
  const std::size_t lo = n >= static_cast<std::size_t>(radius) ? n - radius : 0;
  const std::size_t hi = std::min(c.size() - 1, n + radius);
  for (std::size_t j = lo; j <= hi; ++j) {
    if (j < n && c[j] >= c[n]) return false;  // ties go to the first of equal values
    if (j > n && c[j] > c[n]) return false;
  }
  return true;
}

void fragmentAround(const EqualizedContour &contour, int vertex, int half_length, ComplexSequence &fragment) {
  fragment.assign(2 * static_cast<std::size_t>(half_length), Complex(0.0, 0.0));
  const int elements = static_cast<int>(contour.elementCount());
  for (int m = 0; m < 2 * half_length; ++m) {
    const int r = vertex - half_length + m;
    if (r >= 0 && r < elements) fragment[m] = contour.element(r);
  }
}

}  // namespace

bool SpecialPointParams::validate(std::string *why) const {
  if (!(threshold > 0.0 && threshold < 1.0)) return invalid(why, "special_points.threshold must lie in (0, 1)");
  if (suppression_radius < 0) return invalid(why, "special_points.suppression_radius must be >= 0");
  if (fragment_half_length < 1) return invalid(why, "special_points.fragment_half_length must be >= 1");
  if (!(max_arm_length >= 0.0)) return invalid(why, "special_points.max_arm_length must be >= 0");
  if (!(max_arm_rms > 0.0)) return invalid(why, "special_points.max_arm_rms must be > 0");
  return true;
}

std::vector<SpecialPoint> findSpecialPoints(const ComplexSequence &raw_points, const EqualizedContour &contour,
                                            const CornerResponse &response, const CornerFilterParams &filter,
                                            const SpecialPointParams &params) {
  std::vector<SpecialPoint> points;
  SpareElements<SpecialPoint> spare;
  std::vector<double> arc;
  findSpecialPoints(raw_points, contour, response, filter, params, points, spare, arc);
  return points;
}

void findSpecialPoints(const ComplexSequence &raw_points, const EqualizedContour &contour,
                       const CornerResponse &response, const CornerFilterParams &filter,
                       const SpecialPointParams &params, std::vector<SpecialPoint> &points,
                       SpareElements<SpecialPoint> &spare, std::vector<double> &arc) {
  const std::vector<double> &c = response.response;
  if (c.size() < 3 || raw_points.size() < 2) return;
  const int s = filter.arm_elements;
  const int radius = params.suppression_radius > 0 ? params.suppression_radius : s;
  const double step = contour.step;
  bool have_arc = false;  // the arc lengths are computed on the first special point only

  for (std::size_t n = 1; n + 1 < c.size(); ++n) {
    if (c[n] < params.threshold || !isLocalMaximum(c, n, radius)) continue;
    if (!have_arc) arcLengths(raw_points, arc);
    have_arc = true;

    SpecialPoint &point = spare.append(points);
    point.response = c[n];
    point.turn = response.turn[n];
    point.contour = contour.segment;
    point.vertex = static_cast<int>(n);
    point.sub_element = parabolicPeak(c[n - 1], c[n], c[n + 1]);
    const double at = (static_cast<double>(n) + point.sub_element) * step;
    Complex vertex = pointAtArcLength(raw_points, arc, at);

    // Arm directions from the window's chords, refined by line fits to the raw points.
    Line arm1{contour.vertices[n - s], contour.vertices[n] - contour.vertices[n - s]};
    Line arm2{contour.vertices[n], contour.vertices[n + s] - contour.vertices[n]};
    arm1.direction /= magnitude(arm1.direction);
    arm2.direction /= magnitude(arm2.direction);
    if (params.refine_vertex) {
      Line fit1, fit2;
      Complex refined;
      const double margin = 0.5 * step, reach = s * step;
      if (fitArm(raw_points, arc, at, -1, margin, reach, params, fit1) &&
          fitArm(raw_points, arc, at, +1, margin, reach, params, fit2) && intersect(fit1, fit2, refined) &&
          magnitude(refined - vertex) < 2.0 * step) {
        vertex = refined;
        arm1 = fit1;
        arm2 = fit2;
      }
    }
    point.position = toEigen(vertex);
    const Complex back = -arm1.direction, ahead = arm2.direction;
    point.corner_angle = std::acos(std::clamp((back * std::conj(ahead)).real(), -1.0, 1.0));
    point.orientation = std::arg(back + ahead);
    fragmentAround(contour, point.vertex, params.fragment_half_length, point.fragment);
  }
}

}  // namespace contour_reg
