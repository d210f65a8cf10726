#pragma once
/// @file types.h
/// Basic types of the contour pipeline. The paper writes every 2-D vector as a
/// complex number x + iy; so does this code.

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

/// True when both coordinates are finite numbers.
inline bool isFinite(const Complex &c) { return std::isfinite(c.real()) && std::isfinite(c.imag()); }

}  // namespace contour_reg
