#include "contour_reg/odometry/odometry.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <vector>

#include <Eigen/Cholesky>

#include "contour_reg/io/pose2d.h"
#include "contour_reg/odometry/local_map.h"

namespace contour_reg::odometry {

using io::between;
using io::compose;
using io::scaled;
using io::toMatrix;
using io::toPose;

namespace {

// m/s: faster than any robot that carries a 2-D LIDAR drives.
constexpr double kFastestRobot = 100.0;

// Whether the wheel odometry's `increment` over `dt` s measures a motion: finite, and no faster
// than kFastestRobot. One that is not is a corrupt sample (a log's 1e300 m) or a reset of the
// odometry's frame: no measurement of the robot's motion, it is neither a guess, nor fused, nor
// a bridge, nor a deskewing twist.
bool measuresMotion(const io::Pose2D &increment, double dt) {
  return std::isfinite(increment.x + increment.y + increment.yaw) &&
         std::hypot(increment.x, increment.y) <= kFastestRobot * dt;
}

// The laser's motion between scans a and b of the log by the wheel odometry, when both have it
// and it measures a motion (measuresMotion) over their interval, at least `usual_interval` s: a
// LIDAR takes its scans no faster than its rate (wheelMotionOverSweep).
std::optional<io::Pose2D> wheelMotion(const io::ScanLog &log, const io::LogEntry &a, const io::LogEntry &b,
                                      double usual_interval) {
  if (!a.odometry || !b.odometry) return std::nullopt;
  const io::Pose2D robot = between(*a.odometry, *b.odometry);
  if (!measuresMotion(robot, std::max(b.scan.stamp - a.scan.stamp, usual_interval))) return std::nullopt;
  return log.laser_pose ? io::laserMotion(robot, *log.laser_pose) : robot;
}

// The covariance of wheelMotion(log, a, b, ...) (it has one) under `noise`, in the laser's frame.
Eigen::Matrix3d wheelMotionCovariance(const io::ScanLog &log, const io::LogEntry &a, const io::LogEntry &b,
                                      const WheelNoise &noise) {
  const io::Pose2D robot = between(*a.odometry, *b.odometry);
  const Eigen::Matrix3d covariance = wheelCovariance(robot, noise);
  // The laser's motion is M^-1 r M: robotCovariance with the inverse mounting.
  return log.laser_pose ? io::robotCovariance(covariance, robot, between(*log.laser_pose, io::Pose2D{})) : covariance;
}

// The 99.9 % quantile of chi-square with 3 degrees of freedom, and with 2.
constexpr double kChiSquare3 = 16.27, kChiSquare2 = 13.82;

// How well a prediction of the scan-to-scan motion has done so far: the mean squared error of
// its predictions against the motions the registrations found, per component (x m, y m, yaw rad).
struct PredictionRecord {
  Eigen::Array3d squares = Eigen::Array3d::Zero();
  int steps = 0;

  void add(const io::Pose2D &predicted, const io::Pose2D &found) {
    const io::Pose2D error = between(found, predicted);
    squares += Eigen::Array3d(error.x * error.x, error.y * error.y, error.yaw * error.yaw);
    ++steps;
  }
};

// a - b per component (x m, y m, yaw rad), the turn wrapped to (-pi, pi].
Eigen::Array3d difference(const io::Pose2D &a, const io::Pose2D &b) {
  return {a.x - b.x, a.y - b.y, std::remainder(a.yaw - b.yaw, 2.0 * M_PI)};
}

// What the odometry expects of one scan interval, and how far off that can be: per component
// (x m, y m, yaw rad), the largest variance of the chosen prediction's errors that its record
// allows (none before the first converged step).
struct Prediction {
  io::Pose2D motion;
  std::optional<Eigen::Array3d> variance;
};

// The upper 99.9 % confidence bound of a variance whose mean squared error over `steps`
// samples is `mean_square`: steps x mean_square over the 0.1 % quantile of chi-square with
// `steps` degrees of freedom (Wilson-Hilferty); none while so few steps bound nothing.
std::optional<Eigen::Array3d> varianceBound(const Eigen::Array3d &mean_square, int steps) {
  if (steps < 1) return std::nullopt;
  const double n = steps, quantile = n * std::pow(1.0 - 2.0 / (9.0 * n) - 3.09 * std::sqrt(2.0 / (9.0 * n)), 3);
  if (!(quantile > 0.0)) return std::nullopt;
  return mean_square * (n / quantile);
}

// The motion expected over a registration's interval (a failed one is bridged by it): the
// wheels' and the constant-velocity prediction, component by component, each weighted by the
// inverse of its mean squared error so far, so that whichever has predicted the registrations
// better decides (the last motion where the wheels slip). Where the two differ by more than
// their errors allow, the motion changed (a turn begun between a slow LIDAR's scans) and only
// the wheels measured it: the wheels alone. The wheels alone, too, until there is a record to
// weigh them by; the last motion alone without wheels. With it, the variance bound of the
// record of what it took.
Prediction predict(const std::optional<io::Pose2D> &wheel, const PredictionRecord &by_wheel, const io::Pose2D &velocity,
                   const PredictionRecord &by_velocity) {
  const auto bound = [](const PredictionRecord &r) { return varianceBound(r.squares / std::max(r.steps, 1), r.steps); };
  if (!wheel) return {velocity, bound(by_velocity)};
  if (by_wheel.steps == 0 || by_velocity.steps == 0) return {*wheel, bound(by_wheel)};
  const Eigen::Array3d a = by_wheel.squares / by_wheel.steps, b = by_velocity.squares / by_velocity.steps;
  const Eigen::Array3d gap = difference(*wheel, velocity);
  // Apart by more than their records allow: chi-square with 3 degrees of freedom, 99.9 %.
  if ((gap.square() / (a + b).max(1e-12)).sum() > kChiSquare3) return {*wheel, bound(by_wheel)};
  // Weight of the wheels, per component: 1/a over 1/a + 1/b is b over a + b; the mean squared
  // error of the weighted mean is ab / (a + b), bounded over the shorter record.
  const Eigen::Array3d w = (a + b > 0.0).select(b / (a + b), 0.5);
  return {{velocity.x + w(0) * gap(0), velocity.y + w(1) * gap(1), velocity.yaw + w(2) * gap(2)},
          varianceBound((a + b > 0.0).select(a * b / (a + b), 0.0), std::min(by_wheel.steps, by_velocity.steps))};
}

// Of an ambiguous registration's alternatives (distinct motions that fit the scans about as
// well, RegistrationResult::alternatives), the one the prediction decides for: the only one
// it allows (chi-square with 3 degrees of freedom, 99.9 %, on the sum of the prediction's
// and the motion's variance), where the region it allows is too small to hold another
// motion as far from it as the other alternatives (motionDistance): a motion two periods
// along a row of doors is as far beyond it as the one a period along. `motions` are the
// alternatives over the interval, in the earlier scan's frame; none when undecided.
std::optional<std::size_t> decideBetween(const Prediction &prediction, const std::vector<io::Pose2D> &motions,
                                         const std::vector<RejectedMotion> &alternatives) {
  if (!prediction.variance || motions.size() < 2) return std::nullopt;
  std::optional<std::size_t> allowed;
  for (std::size_t i = 0; i < motions.size(); ++i) {
    const Eigen::Array3d variance = *prediction.variance + alternatives[i].covariance.diagonal().array().max(0.0);
    if (!(variance > 0.0).all()) return std::nullopt;  // NaN too
    if ((difference(motions[i], prediction.motion).square() / variance).sum() > kChiSquare3) continue;
    if (allowed) return std::nullopt;  // the prediction allows two
    const Eigen::Array3d half_width = (kChiSquare3 * variance).sqrt();
    const double extent = 2.0 * (std::hypot(half_width(0), half_width(1)) + half_width(2));
    for (std::size_t j = 0; j < motions.size(); ++j)
      if (j != i && extent >= motionDistance(alternatives[i].transform, alternatives[j].transform)) return std::nullopt;
    allowed = i;
  }
  return allowed;
}

enum class Fused { kNo, kConverged, kPinned };

// Whether the scans left a direction of `match` free and say what they pin of the rest: an
// unconstrained verdict, or a converged estimate marked degenerate.
bool leavesADirectionFree(const MatchResult &match) { return match.pinned && (!match.converged || match.degenerate); }

// Fuses `match` with the wheels' increment `wheel` (covariance `wheel_covariance`): a converged
// registration by its covariance, one that leaves a direction free by what it pins. Nothing
// changes when there is nothing to fuse or the two disagree beyond their uncertainties.
Fused fuseWithWheels(MatchResult &match, const io::Pose2D &wheel, const Eigen::Matrix3d &wheel_covariance) {
  const bool by_pinned = leavesADirectionFree(match);
  const Eigen::LLT<Eigen::Matrix3d> covariance(match.covariance);
  if (!by_pinned && (!match.converged || !match.covariance.allFinite() || covariance.info() != Eigen::Success))
    return Fused::kNo;
  const std::optional<FusedMotion> fused =
      by_pinned ? fuse(toPose(match.pinned->transform), match.pinned->information, wheel, wheel_covariance)
                : fuse(toPose(match.transform), covariance.solve(Eigen::Matrix3d::Identity()), wheel, wheel_covariance);
  if (!fused || fused->disagreement > (by_pinned ? kChiSquare2 : kChiSquare3)) return Fused::kNo;
  match.transform = toMatrix(fused->motion);
  match.covariance = fused->covariance;
  match.converged = true;
  match.degenerate = false;
  match.status.clear();
  match.reason.clear();
  return by_pinned ? Fused::kPinned : Fused::kConverged;
}

// The value of an enum whose values are named by `names` in order; none for another name.
template <class Enum>
std::optional<Enum> enumNamed(const std::vector<std::string> &names, const std::string &name) {
  const auto at = std::find(names.begin(), names.end(), name);
  if (at == names.end()) return std::nullopt;
  return static_cast<Enum>(at - names.begin());
}

// The run's trajectory and steps, found in the laser's frame, in the robot's.
void toRobotFrame(OdometryRun &run, const io::Pose2D &laser_pose) {
  for (io::StampedPose &p : run.trajectory) p.pose = io::robotMotion(p.pose, laser_pose);
  for (OdometryStep &step : run.steps) {
    step.covariance = io::robotCovariance(step.covariance, step.motion, laser_pose);
    step.motion = io::robotMotion(step.motion, laser_pose);
  }
  run.frame = Frame::kRobot;
}

}  // namespace

const std::vector<std::string> &guessSourceNames() {
  static const std::vector<std::string> names{"zero", "odom", "velocity"};
  return names;
}

const std::vector<std::string> &frameNames() {
  static const std::vector<std::string> names{"robot", "laser"};
  return names;
}

std::optional<GuessSource> guessSourceNamed(const std::string &name) {
  return enumNamed<GuessSource>(guessSourceNames(), name);
}

std::optional<Frame> frameNamed(const std::string &name) { return enumNamed<Frame>(frameNames(), name); }

Twist2D twistOver(const io::Pose2D &motion, double dt) { return {motion.x / dt, motion.y / dt, motion.yaw / dt}; }

namespace {

// The twist of the robot's `motion` over `dt` s, in the laser's frame when the log gives its mounting.
Twist2D sensorTwist(const io::ScanLog &log, const io::Pose2D &motion, double dt) {
  return twistOver(log.laser_pose ? io::laserMotion(motion, *log.laser_pose) : motion, dt);
}

}  // namespace

double medianScanInterval(const io::ScanLog &log) {
  std::vector<double> intervals;
  std::optional<double> previous;
  for (const io::LogEntry &entry : log.entries) {
    if (!entry.odometry) continue;
    if (previous) intervals.push_back(entry.scan.stamp - *previous);
    previous = entry.scan.stamp;
  }
  if (intervals.empty()) return 0.0;
  std::nth_element(intervals.begin(), intervals.begin() + intervals.size() / 2, intervals.end());
  return intervals[intervals.size() / 2];
}

std::optional<SweepMotion> wheelMotionOverSweep(const io::ScanLog &log, std::size_t k) {
  return wheelMotionOverSweep(log, k, medianScanInterval(log));
}

std::optional<SweepMotion> wheelMotionOverSweep(const io::ScanLog &log, std::size_t k, double usual_interval) {
  if (k >= log.entries.size()) return std::nullopt;
  const LaserScan &scan = log.entries[k].scan;
  const double begin = scan.stamp;
  const double end = begin + scan.time_increment * static_cast<double>(scan.ranges.size());
  if (log.wheel_odometry.empty()) {
    // The scans' own odometry: one twist, the motion to the next scan with odometry over their
    // interval, or over the log's usual interval where theirs is shorter. A LIDAR takes its
    // scans no faster than its rate; a shorter interval is a logger's stamp (intel's logger
    // wrote scans in bursts of up to 14, stamped a millisecond apart and a whole scan's turn
    // apart), and that turn divided into it would be a twist many times too fast.
    if (!log.entries[k].odometry) return std::nullopt;
    for (std::size_t j = k + 1; j < log.entries.size(); ++j) {
      if (!log.entries[j].odometry) continue;
      const double dt = std::max(log.entries[j].scan.stamp - begin, usual_interval);
      const io::Pose2D increment = between(*log.entries[k].odometry, *log.entries[j].odometry);
      if (!(dt > 1e-6) || !measuresMotion(increment, dt)) return std::nullopt;
      return SweepMotion(sensorTwist(log, increment, dt));
    }
    return std::nullopt;
  }
  const std::vector<io::StampedPose> &samples = log.wheel_odometry;
  // The interval that holds the first beam starts at the last sample at or before it.
  auto first = std::upper_bound(samples.begin(), samples.end(), begin,
                                [](double t, const io::StampedPose &p) { return t < p.stamp; });
  if (first == samples.begin()) return std::nullopt;
  --first;
  std::optional<SweepMotion> motion;
  for (auto a = first; a + 1 != samples.end() && (a == first || a->stamp < end); ++a) {
    const double dt = (a + 1)->stamp - a->stamp;
    const io::Pose2D increment = between(a->pose, (a + 1)->pose);
    // Repeated stamps carry no velocity, a jump (measuresMotion) no motion.
    if (!(dt > 1e-6) || !measuresMotion(increment, dt)) continue;
    const Twist2D twist = sensorTwist(log, increment, dt);
    if (!motion)
      motion = SweepMotion(twist);
    else
      motion->changes.push_back({a->stamp - begin, twist});
  }
  return motion;
}

io::Trajectory wheelOdometry(const io::ScanLog &log) {
  io::Trajectory trajectory;
  std::optional<io::Pose2D> origin;
  for (const io::LogEntry &entry : log.entries) {
    if (!entry.odometry) continue;
    if (!origin) origin = entry.odometry;
    trajectory.push_back({entry.scan.stamp, between(*origin, *entry.odometry)});
  }
  return trajectory;
}

OdometryRun runOdometry(const io::ScanLog &log, ScanMatcher &matcher, const OdometryOptions &options) {
  OdometryRun run;
  const auto &entries = log.entries;
  if (entries.empty()) return run;
  std::vector<io::Pose2D> poses{io::Pose2D{}};
  run.trajectory.push_back({entries[0].scan.stamp, poses[0]});
  io::Pose2D velocity_motion{};  // last scan-to-scan motion
  double velocity_dt = 0.0;
  // Without wheel odometry, a scan is first deskewed by the last motion; not after a scan that
  // registered as taken, which says the motion changed (a turn or a drive ended).
  bool last_scan_as_taken = false;
  PredictionRecord wheel_record, velocity_record;  // the two predictions' errors on the converged steps
  std::size_t keyframe = 0;
  // Each scan's motion over its sweep, set when the scan is matched as the source; the first scan's
  // by the wheel odometry alone, when the log has it.
  std::vector<SweepMotion> sweeps(entries.size());
  const double usual_interval = medianScanInterval(log);
  if (options.deskew && entries[0].scan.time_increment > 0.0)
    if (const std::optional<SweepMotion> first = wheelMotionOverSweep(log, 0, usual_interval)) sweeps[0] = *first;
  // The local map: its keyframes (oldest first) and the scan drawn of them at the newest.
  const bool mapping = options.local_map_keyframes > 0;
  std::vector<std::size_t> map_keyframes{0};
  LaserScan map;
  auto redrawMap = [&]() {
    std::vector<MapKeyframe> keyframes;
    for (std::size_t j : map_keyframes) keyframes.push_back({&entries[j].scan, sweeps[j], poses[j]});
    map = renderLocalMap(keyframes);
  };
  if (mapping) redrawMap();
  for (std::size_t k = 1; k < entries.size(); ++k) {
    const std::size_t reference = (options.keyframes || mapping) ? keyframe : k - 1;
    // The scan registered against: the reference scan, or the map drawn at it (deskewed already).
    const LaserScan &target = mapping ? map : entries[reference].scan;
    const SweepMotion target_sweep = mapping ? SweepMotion{} : sweeps[reference];
    const io::Pose2D previous = poses[k - 1];
    const double dt = entries[k].scan.stamp - entries[k - 1].scan.stamp;

    // Where the scan is expected, by constant velocity and by wheel odometry.
    // The previous motion scaled to this interval; no prediction across stamp jumps.
    const double velocity_scale = velocity_dt > 1e-3 ? std::clamp(dt / velocity_dt, 0.0, 3.0) : 0.0;
    const io::Pose2D velocity_step = scaled(velocity_motion, velocity_scale);
    const io::Pose2D by_velocity = compose(previous, velocity_step);
    const auto wheel = wheelMotion(log, entries[k - 1], entries[k], usual_interval);
    io::Pose2D expected = previous;
    if (options.guess == GuessSource::kOdometry && wheel) expected = compose(previous, *wheel);
    if (options.guess == GuessSource::kConstantVelocity) expected = by_velocity;

    const io::Pose2D guess = between(poses[reference], expected);
    const bool deskewing = options.deskew && entries[k].scan.time_increment > 0.0;
    // The motion over this scan's sweep: the wheel odometry's when the log has it, else the last motion.
    const std::optional<SweepMotion> wheel_sweep =
        deskewing ? wheelMotionOverSweep(log, k, usual_interval) : std::nullopt;
    const bool by_wheel = wheel_sweep.has_value();
    if (by_wheel)
      sweeps[k] = *wheel_sweep;
    else if (deskewing && velocity_dt > 1e-3 && !last_scan_as_taken)
      sweeps[k] = twistOver(velocity_motion, velocity_dt);
    // The registration of the scan deskewed by `source_sweep`: from the guess, and on a failure
    // once more from the constant-velocity prediction when that is a different guess (a turn or
    // a drive that goes on, where the first guess was "no motion"). `tries` counts the registrations.
    const io::Pose2D velocity_guess = between(poses[reference], by_velocity);
    const io::Pose2D guess_gap = between(guess, velocity_guess);
    const bool velocity_differs = options.retry_with_velocity && velocity_scale > 0.0 &&
                                  (std::hypot(guess_gap.x, guess_gap.y) > 0.05 || std::abs(guess_gap.yaw) > 0.05);
    std::size_t tries = 0;
    const auto registerDeskewed = [&](const SweepMotion &source_sweep) {
      ++tries;
      MatchResult found = matcher.match(target, entries[k].scan, toMatrix(guess), target_sweep, source_sweep);
      if (found.converged || !velocity_differs) return found;
      ++tries;
      MatchResult second = matcher.match(target, entries[k].scan, toMatrix(velocity_guess), target_sweep, source_sweep);
      second.milliseconds += found.milliseconds;
      if (second.converged) return second;
      found.milliseconds = second.milliseconds;
      return found;
    };
    MatchResult match = registerDeskewed(sweeps[k]);
    // Without wheel odometry the scan was deskewed by the last motion; where a turn or a drive
    // ended within the interval, that bends a scan taken straight. A failure gets one more try
    // with the scan as taken, and the scan stays so.
    bool as_taken = false;
    if (!match.converged && deskewing && !by_wheel && !sweeps[k].isZero()) {
      const double failed_ms = match.milliseconds;
      const MatchResult taken = registerDeskewed(SweepMotion{});
      as_taken = taken.converged;
      if (as_taken) {
        match = taken;
        sweeps[k] = SweepMotion{};
      }
      match.milliseconds = failed_ms + taken.milliseconds;
    }
    run.stats.recovered_by_retry += match.converged && tries > 1;
    // Otherwise deskewed again with the motion this registration found over the interval,
    // rather than the last one. That motion is the scan's sweep from here on, as the next
    // registration's target, even where this second registration fails (on a bent target).
    if (deskewing && !by_wheel && !as_taken && match.converged && dt > 1e-3 && reference == k - 1) {
      const Twist2D better = twistOver(toPose(match.transform), dt);
      const MatchResult again = matcher.match(target, entries[k].scan, match.transform, target_sweep, better);
      const double both_ms = match.milliseconds + again.milliseconds;
      if (again.converged) match = again;
      sweeps[k] = better;
      match.milliseconds = both_ms;
    }
    // Repeated structure (a row of doors) leaves distinct motions that fit the scans as well;
    // the motion the odometry expects over the interval may allow only one of them.
    const Prediction expected_motion = predict(wheel, wheel_record, velocity_step, velocity_record);
    if (!match.converged && !match.alternatives.empty()) {
      std::vector<io::Pose2D> motions;
      for (const RejectedMotion &alternative : match.alternatives)
        motions.push_back(between(previous, compose(poses[reference], toPose(alternative.transform))));
      if (const std::optional<std::size_t> chosen = decideBetween(expected_motion, motions, match.alternatives)) {
        match.transform = match.alternatives[*chosen].transform;
        match.covariance = match.alternatives[*chosen].covariance;
        match.converged = true;
        match.status.clear();
        match.reason.clear();
        ++run.stats.decided_by_prediction;
      }
    }
    // The wheels are fused with every registration when they are the guess, and otherwise with
    // those that leave a direction free: there they decide that direction only, where a bridge
    // would take the whole step from them.
    const auto wheel_over_step =
        reference == k - 1 ? wheel : wheelMotion(log, entries[reference], entries[k], usual_interval);
    if ((options.guess == GuessSource::kOdometry || leavesADirectionFree(match)) && options.fuse_wheel_odometry &&
        wheel_over_step) {
      const Fused fused = fuseWithWheels(
          match, *wheel_over_step, wheelMotionCovariance(log, entries[reference], entries[k], options.wheel_noise));
      run.stats.fused += fused != Fused::kNo;
      run.stats.pinned_by_wheels += fused == Fused::kPinned;
    }
    if (match.converged && match.degenerate && options.reject_degenerate) {
      match.converged = false;
      match.status = "degenerate";
      match.reason = "converged, but the scans leave a direction unconstrained";
    }
    ++run.stats.registrations;
    if (options.on_match) options.on_match(reference, k, target, match, toMatrix(guess));
    run.stats.milliseconds.push_back(match.milliseconds);
    io::Pose2D pose;
    if (match.converged) {
      pose = compose(poses[reference], toPose(match.transform));
    } else {
      ++run.stats.failures;
      run.stats.degenerate += match.status == "degenerate";
      ++run.stats.failure_reasons[match.status];
      run.stats.failed_scans.push_back(k);
      pose = compose(previous, expected_motion.motion);
    }
    if (match.converged && wheel) {
      const io::Pose2D found = between(previous, pose);
      wheel_record.add(*wheel, found);
      velocity_record.add(velocity_step, found);
    }
    poses.push_back(pose);
    run.trajectory.push_back({entries[k].scan.stamp, pose});
    run.steps.push_back({reference, k, match.converged, match.converged ? std::string() : match.status,
                         between(poses[reference], pose),
                         match.converged ? match.covariance : Eigen::Matrix3d::Zero()});
    velocity_motion = between(previous, pose);
    velocity_dt = dt;
    last_scan_as_taken = as_taken;

    if (options.keyframes || mapping) {
      const io::Pose2D from_keyframe = between(poses[keyframe], pose);
      if (!match.converged || std::hypot(from_keyframe.x, from_keyframe.y) >= options.keyframe_distance ||
          std::abs(from_keyframe.yaw) >= options.keyframe_angle) {
        keyframe = k;
        if (mapping) {
          if (!match.converged) map_keyframes.clear();  // a bridged pose is no place to draw a map from
          map_keyframes.push_back(k);
          if (map_keyframes.size() > options.local_map_keyframes) map_keyframes.erase(map_keyframes.begin());
          redrawMap();
        }
      }
    }
    if (options.progress) options.progress(k + 1, entries.size());
  }
  if (options.frame == Frame::kRobot && log.laser_pose) toRobotFrame(run, *log.laser_pose);
  return run;
}

std::string frameDescription(Frame frame, const io::ScanLog &log) {
  char text[160];
  if (frame == Frame::kRobot && log.laser_pose)
    std::snprintf(text, sizeof text,
                  "frame: robot (base_link); the laser is mounted at x %.3f m, y %.3f m, yaw %.2f deg",
                  log.laser_pose->x, log.laser_pose->y, log.laser_pose->yaw * 180.0 / M_PI);
  else
    std::snprintf(text, sizeof text, "frame: laser%s", log.laser_pose ? "" : " (the log gives no mounting)");
  return text;
}

}  // namespace contour_reg::odometry
