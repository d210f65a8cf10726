#include "contour_reg/core/deskew.h"

#include <algorithm>
#include <cmath>
#include <limits>

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

bool SweepMotion::isZero() const {
  for (const Change &change : changes)
    if (!change.twist.isZero()) return false;
  return twist.isZero();
}

bool SweepMotion::operator==(const SweepMotion &other) const {
  auto same = [](const Twist2D &a, const Twist2D &b) { return a.vx == b.vx && a.vy == b.vy && a.wz == b.wz; };
  if (!same(twist, other.twist) || changes.size() != other.changes.size()) return false;
  for (std::size_t i = 0; i < changes.size(); ++i)
    if (changes[i].from != other.changes[i].from || !same(changes[i].twist, other.changes[i].twist)) return false;
  return true;
}

void deskewPolarCode(ComplexSequence &code, const Sweep &sweep) {
  if (!sweep.moving()) return;
  const double dt = sweep.time_increment;
  const SweepMotion &motion = sweep.motion;
  // One constant twist at a time. The sensor's pose where the twist begins is (origin,
  // facing); within it, integrateTwist at the beam's time since then, with the heading's unit
  // vector advanced by one fixed turn per beam instead of a sine and cosine per beam.
  Complex origin(0.0, 0.0), facing(1.0, 0.0);
  double start = 0.0;
  Twist2D twist = motion.twist;
  std::size_t n = 0;
  for (std::size_t next = 0;; ++next) {
    const bool last = next >= motion.changes.size();
    const double end = last ? std::numeric_limits<double>::infinity() : std::max(motion.changes[next].from, start);
    const Complex velocity(twist.vx, twist.vy);
    const double wz = twist.wz;
    const bool turning = std::abs(wz) > 1e-9;
    const Complex turn_per_beam = std::polar(1.0, wz * dt);
    Complex heading = std::polar(1.0, wz * (dt * static_cast<double>(n) - start));  // exp(i wz t)
    for (; n < code.size() && dt * static_cast<double>(n) < end; ++n, heading *= turn_per_beam) {
      if (!isFinite(code[n])) continue;
      const double t = dt * static_cast<double>(n) - start;
      const Complex position =
          turning ? Complex(heading.imag(), 1.0 - heading.real()) / wz * velocity : Complex(t, 0.0) * velocity;
      code[n] = origin + facing * (position + heading * code[n]);
    }
    if (last || n >= code.size()) return;
    Complex moved;
    double turned = 0.0;
    integrateTwist(twist, end - start, moved, turned);
    origin += facing * moved;
    facing *= std::polar(1.0, turned);
    start = end;
    twist = motion.changes[next].twist;
  }
}

void deskewedPolarCode(const LaserScan &scan, const SweepMotion &motion, ComplexSequence &code) {
  polarCode(scan, code);
  deskewPolarCode(code, Sweep{scan.time_increment, motion});
}

ComplexSequence deskewedPolarCode(const LaserScan &scan, const SweepMotion &motion) {
  ComplexSequence code;
  deskewedPolarCode(scan, motion, code);
  return code;
}

}  // namespace contour_reg
