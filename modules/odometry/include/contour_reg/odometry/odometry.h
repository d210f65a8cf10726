#pragma once
/// @file odometry.h
/// Laser odometry: chains scan registrations into a trajectory, either scan to scan or
/// against keyframes (laser_scan_matcher's scheme: match against the last keyframe, take
/// a new one after enough motion or a failed match).

#include <cstddef>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "contour_reg/io/scan_log.h"
#include "contour_reg/io/trajectory.h"
#include "contour_reg/odometry/scan_matcher.h"
#include "contour_reg/odometry/wheel_fusion.h"

namespace contour_reg::odometry {

/// Where the initial guess of each registration comes from.
enum class GuessSource {
  kZero,              ///< no motion since the previous scan
  kOdometry,          ///< the log's wheel odometry between the two scans, also a prior (fuse_wheel_odometry)
  kConstantVelocity,  ///< the previous motion, scaled by the time between scans
};

/// The frame a run's trajectory and steps are given in.
enum class Frame {
  kRobot,  ///< the robot's (base_link), where relations, wheel odometry and ROS consumers speak
  kLaser,  ///< the laser's, where the scans are taken
};

/// The names the command line and Python give the guess sources (zero, odom, velocity) and the
/// frames (robot, laser), in the enums' order, and the value of a name; none for another name.
const std::vector<std::string> &guessSourceNames();
const std::vector<std::string> &frameNames();
std::optional<GuessSource> guessSourceNamed(const std::string &name);
std::optional<Frame> frameNamed(const std::string &name);

struct OdometryOptions {
  GuessSource guess = GuessSource::kZero;
  /// The frame of the trajectory and the steps. The scans are registered in the laser's frame
  /// and the wheel odometry is brought into it through the log's mounting (ScanLog::laser_pose);
  /// kRobot gives the result in the robot's frame when the log knows the mounting. A log without
  /// one is taken to have the laser at the robot's centre, and its result is the laser's.
  Frame frame = Frame::kRobot;
  bool keyframes = false;
  double keyframe_distance = 0.3;  ///< m of motion from the keyframe that starts a new one
  double keyframe_angle = 0.2;     ///< rad of turn from the keyframe that starts a new one
  /// > 0: each scan is registered against a local map of the last this many keyframes
  /// (local_map.h), keyframes taken as with `keyframes`; a failed registration starts the map
  /// anew from its scan. 0: against the previous scan (or the last keyframe).
  std::size_t local_map_keyframes = 0;
  /// A registration that fails from the guess is tried once more from the constant-velocity
  /// prediction (when that differs); only if both fail does the scan count as failed.
  bool retry_with_velocity = true;
  /// A registration that converged but says it is degenerate (MatchResult::degenerate) is
  /// treated as failed: bridged, not chained, and counted.
  bool reject_degenerate = true;
  /// With the wheel odometry as the guess, each contour registration is fused with the wheels'
  /// increment over the same interval (wheel_fusion.h): a converged one by its covariance, one
  /// that leaves a direction free (an unconstrained verdict, a degenerate estimate) by what it
  /// pins (MatchResult::pinned), so that the wheels decide that direction only. With another
  /// guess, only those that leave a direction free are fused: a bridge would take the whole
  /// step from the wheels. The two must agree within their uncertainties (chi-square, 99.9 %);
  /// where they do not, the scans' answer stands, or the scan stays failed. Other methods, and
  /// scans without odometry, are chained as they are.
  bool fuse_wheel_odometry = true;
  WheelNoise wheel_noise;  ///< the wheels' error model for the fusion
  /// Scans that carry beam timing (LaserScan::time_increment), the first one included, are
  /// deskewed (deskew.h) with the motion over their sweep: the wheel odometry's
  /// (wheelMotionOverSweep) when the log has it; otherwise the constant-velocity prediction (the
  /// previous motion over its interval), then, once registered, the motion that registration
  /// found, and registered again (scan to scan only). Scans without beam timing are left as
  /// they are. Simulated continuous runs: docs/experiment.md.
  bool deskew = true;
  /// Called after every scan with (scans done, scans in all).
  std::function<void(std::size_t, std::size_t)> progress;
  /// Called after every registration with (reference scan index, scan index, the scan it was
  /// registered against: the reference scan or the local map drawn at it, result, the guess it
  /// started from, source to target).
  std::function<void(std::size_t, std::size_t, const LaserScan &, const MatchResult &, const Eigen::Matrix3d &)>
      on_match;
};

struct OdometryStats {
  std::size_t registrations = 0;
  std::size_t failures = 0;    ///< not converged (degenerate ones included)
  std::size_t degenerate = 0;  ///< of the failures, those whose status is "degenerate"
  /// Registrations that failed from the guess and converged on a retry: from the
  /// constant-velocity prediction, or, without wheel odometry, with the scan as taken.
  std::size_t recovered_by_retry = 0;
  /// Ambiguous registrations (distinct motions fit the scans as well: repeated structure) where
  /// the prediction over the interval allows one of those motions alone: taken as converged.
  std::size_t decided_by_prediction = 0;
  std::size_t fused = 0;                               ///< registrations fused with the wheel odometry
  std::size_t pinned_by_wheels = 0;                    ///< of those, the ones whose scans left a direction free
  std::vector<double> milliseconds;                    ///< per registration
  std::map<std::string, std::size_t> failure_reasons;  ///< MatchResult::status -> count
  std::vector<std::size_t> failed_scans;               ///< scan indices whose registration failed
};

/// One registration of a run, as a pose-graph back end takes it: the motion from the
/// reference scan to the scan and its covariance, or why there is none.
struct OdometryStep {
  std::size_t reference = 0, scan = 0;  ///< scan indices in the log
  bool converged = false;
  std::string status;                                    ///< "" when converged
  io::Pose2D motion;                                     ///< reference to scan, as chained (bridged when failed)
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();  ///< x, y, yaw; zero when the method gives none or failed
};

struct OdometryRun {
  io::Trajectory trajectory;        ///< one pose per scan, the first at the origin
  std::vector<OdometryStep> steps;  ///< one per registration, in order
  OdometryStats stats;
  Frame frame = Frame::kLaser;  ///< the frame of trajectory and steps
};

/// One line that says which frame results of `log` given in `frame` are in (OdometryRun::frame),
/// and where the laser is mounted, for the head of a trajectory file.
std::string frameDescription(Frame frame, const io::ScanLog &log);

/// The log's own wheel odometry as a trajectory in the robot's frame, starting at the origin
/// with the first scan that has it; scans without it are left out.
io::Trajectory wheelOdometry(const io::ScanLog &log);

/// The constant twist that makes `motion` in `dt` s (dt > 0).
Twist2D twistOver(const io::Pose2D &motion, double dt);

/// The laser's motion over scan k's sweep by the wheel odometry, brought to the laser by the
/// log's mounting: one constant twist per interval of the odometry's samples
/// (ScanLog::wheel_odometry) that the sweep overlaps, the last one held past the last sample.
/// A log that keeps no samples gives one twist from the scans' own odometry: the motion to the
/// next scan over their interval, or over the log's median scan interval (medianScanInterval)
/// where theirs is shorter (a logger that stamped scans in bursts). None when no sample is at
/// or before the scan's stamp, or there is no interval to take a twist from.
std::optional<SweepMotion> wheelMotionOverSweep(const io::ScanLog &log, std::size_t k);

/// The same with the log's medianScanInterval computed once by the caller (`usual_interval`, s):
/// the form for a loop over a log's scans.
std::optional<SweepMotion> wheelMotionOverSweep(const io::ScanLog &log, std::size_t k, double usual_interval);

/// s, the median interval between consecutive scans with odometry of `log` (0 with fewer than two).
double medianScanInterval(const io::ScanLog &log);

/// Runs odometry over `log` with `matcher`. A registration that fails is retried from the
/// constant-velocity prediction (retry_with_velocity); one that fails again is never chained but
/// bridged, and counted in the stats. The bridge combines the wheel odometry's increment (when
/// the log has it, whatever the guess source) and the constant-velocity prediction, each
/// weighted per component by the inverse of its mean squared error against the motions the
/// registrations found so far. The wheels alone where the two differ beyond those errors (the
/// motion changed: a turn the prediction cannot know) or until both have a record; the
/// prediction alone without wheels.
OdometryRun runOdometry(const io::ScanLog &log, ScanMatcher &matcher, const OdometryOptions &options = {});

}  // namespace contour_reg::odometry
