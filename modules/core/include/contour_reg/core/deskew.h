#pragma once
/// @file deskew.h
/// Beyond the paper: motion compensation (deskewing) of a scan taken while moving.
///
/// A spinning LIDAR takes beam n at stamp + n * time_increment (LaserScan::time_increment),
/// each from where the robot is then; on a moving robot a straight wall comes out bent. With
/// the motion over the scan as a constant twist (velocity and yaw rate in the sensor's own
/// frame), the sensor at time t stands at exp(t * twist), and every beam's point is moved from
/// there into the frame of the sensor at the stamp. A motion that changes during the sweep (a
/// turn begun halfway through a slow sweep) is a chain of such twists, one per interval of the
/// wheel odometry's samples. The result is the scan's polar code (contour.h) as a scan taken
/// all at once at its stamp would give it, ready for extractContourFeatures.

#include <vector>

#include "contour_reg/core/contour.h"
#include "contour_reg/core/laser_scan.h"

namespace contour_reg {

/// A constant planar velocity: m/s along x and y, rad/s about z, in the sensor's frame at the stamp.
struct Twist2D {
  double vx = 0.0, vy = 0.0, wz = 0.0;
  bool isZero() const { return vx == 0.0 && vy == 0.0 && wz == 0.0; }
};

/// How the sensor moved over a sweep: at `twist` from the first beam on, and from each
/// change's time on at that change's twist. Every twist is in the sensor's own frame of the
/// moment, so a constant twist needs no change. Implicit from a Twist2D: a constant motion.
struct SweepMotion {
  /// A new velocity from `from` s after the first beam on.
  struct Change {
    double from = 0.0;
    Twist2D twist;
  };
  Twist2D twist;                ///< from the first beam on
  std::vector<Change> changes;  ///< later velocities, in time order

  SweepMotion() = default;
  SweepMotion(const Twist2D &first, std::vector<Change> later = {})  // NOLINT(google-explicit-constructor)
      : twist(first), changes(std::move(later)) {}
  bool isZero() const;
  bool operator==(const SweepMotion &other) const;
};

/// How a scan was taken: beam n (in the order the beams were taken) at n * time_increment s
/// after the first, while the sensor moved by `motion`. The default is a scan taken at once.
struct Sweep {
  double time_increment = 0.0;  ///< s between consecutive beams
  SweepMotion motion;           ///< the sensor's velocity over the sweep
  bool moving() const { return time_increment != 0.0 && !motion.isZero(); }
};

/// The pose, as a complex position and a heading (rad), reached after `t` s at `twist` from the identity.
void integrateTwist(const Twist2D &twist, double t, Complex &position, double &heading);

/// Moves every finite point of `code` (sensor-frame points in the order the beams were taken)
/// from where the sensor was when its beam fired into the frame of the sensor at the first beam.
void deskewPolarCode(ComplexSequence &code, const Sweep &sweep);

/// The deskewed polar code of `scan` into `code` (beam order, NaN for invalid beams). With a
/// time_increment of 0 or no motion it equals polarCode(scan).
void deskewedPolarCode(const LaserScan &scan, const SweepMotion &motion, ComplexSequence &code);

/// The same, returned.
ComplexSequence deskewedPolarCode(const LaserScan &scan, const SweepMotion &motion);

}  // namespace contour_reg
