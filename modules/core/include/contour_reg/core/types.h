#pragma once
/// @file types.h
/// Basic types of the contour pipeline. The paper writes every 2-D vector as a
/// complex number x + iy; so does this code.

#include <algorithm>
#include <cmath>
#include <complex>
#include <vector>

#include <Eigen/Core>

namespace contour_reg {

/// A 2-D point or vector as a complex number, x + iy.
using Complex = std::complex<double>;

/// A sequence of points or elementary vectors (a contour code).
using ComplexSequence = std::vector<Complex>;

inline Eigen::Vector2d toEigen(const Complex &c) { return {c.real(), c.imag()}; }
inline Complex toComplex(const Eigen::Vector2d &v) { return {v.x(), v.y()}; }

/// How far `p` lies from the segment from `a` to `b` (from `a` when the two coincide).
inline double distanceToSegment(const Eigen::Vector2d &p, const Eigen::Vector2d &a, const Eigen::Vector2d &b) {
  const Eigen::Vector2d edge = b - a;
  const double length2 = edge.squaredNorm();
  const double u = length2 > 0.0 ? std::clamp((p - a).dot(edge) / length2, 0.0, 1.0) : 0.0;
  return (a + u * edge - p).norm();
}

/// |c|, the length of a vector. std::abs on a complex number calls hypot, which guards
/// against overflow at several times the cost; LIDAR coordinates in metres never come near
/// it, and this is the inner loop of the matched filter.
inline double magnitude(const Complex &c) { return std::sqrt(c.real() * c.real() + c.imag() * c.imag()); }
/// |c|^2 (std::norm goes through hypot as well).
inline double squaredMagnitude(const Complex &c) { return c.real() * c.real() + c.imag() * c.imag(); }

/// atan2(y, x) within 2.1e-4 rad, nondecreasing in the bearing, at a fraction of the
/// library's cost: for where a search starts, which histogram bin a direction falls in or
/// which returns bracket a bearing, not for a measurement.
inline double approximateAtan2(double y, double x) {
  const double ax = std::abs(x), ay = std::abs(y);
  const double high = ax > ay ? ax : ay, low = ax > ay ? ay : ax;
  if (high == 0.0) return 0.0;
  const double a = low / high, s = a * a;
  double r = ((-0.0464964749 * s + 0.15931422) * s - 0.327622764) * s * a + a;
  if (ay > ax) r = M_PI_2 - r;
  if (x < 0.0) r = M_PI - r;
  return y < 0.0 ? -r : r;
}

/// True when both coordinates are finite numbers.
inline bool isFinite(const Complex &c) { return std::isfinite(c.real()) && std::isfinite(c.imag()); }

}  // namespace contour_reg
