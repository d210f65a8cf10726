#include "contour_reg/core/deskew.h"

#include <cmath>

namespace contour_reg {

void integrateTwist(const Twist2D &twist, double t, Complex &position, double &heading) {
  heading = twist.wz * t;
  // The exponential of SE(2): the velocity turns with the heading along the way.
  const double theta = heading;
  double a = t, b = 0.0;  // position = (a + i b) * (vx + i vy)
  if (std::abs(theta) > 1e-9) {
    a = std::sin(theta) / twist.wz;
    b = (1.0 - std::cos(theta)) / twist.wz;
  }
  position = Complex(a, b) * Complex(twist.vx, twist.vy);
}

void deskewPolarCode(ComplexSequence &code, const Sweep &sweep) {
  if (!sweep.moving()) return;
  // integrateTwist at t = n * time_increment, with the heading's unit vector advanced by one
  // fixed turn per beam instead of a sine and cosine per beam.
  const Complex velocity(sweep.twist.vx, sweep.twist.vy);
  const double wz = sweep.twist.wz;
  const bool turning = std::abs(wz) > 1e-9;
  const Complex turn_per_beam = std::polar(1.0, wz * sweep.time_increment);
  Complex heading(1.0, 0.0);  // exp(i wz t)
  for (std::size_t n = 0; n < code.size(); ++n, heading *= turn_per_beam) {
    if (!isFinite(code[n])) continue;
    const double t = sweep.time_increment * static_cast<double>(n);
    const Complex position =
        turning ? Complex(heading.imag(), 1.0 - heading.real()) / wz * velocity : Complex(t, 0.0) * velocity;
    code[n] = position + heading * code[n];
  }
}

void deskewedPolarCode(const LaserScan &scan, const Twist2D &twist, ComplexSequence &code) {
  polarCode(scan, code);
  deskewPolarCode(code, Sweep{scan.time_increment, twist});
}

ComplexSequence deskewedPolarCode(const LaserScan &scan, const Twist2D &twist) {
  ComplexSequence code;
  deskewedPolarCode(scan, twist, code);
  return code;
}

}  // namespace contour_reg
