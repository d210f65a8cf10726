#pragma once
// Options several subcommands share: how to read a scan source, and the settings of the
// registration methods.

#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "contour_reg/core/equalization.h"
#include "contour_reg/evaluation/metrics.h"
#include "contour_reg/io/read_log.h"
#include "contour_reg/odometry/odometry.h"
#include "contour_reg/odometry/scan_matcher.h"

namespace contour_reg::cli {

/// A check that the value is a number in [low, high] (or (low, high] when `open_low`), with
/// a message that names the bounds as the help text writes them.
CLI::Validator inRange(double low, double high, bool open_low = false);
/// Numbers > 0.
inline CLI::Validator positive() { return inRange(0.0, std::numeric_limits<double>::infinity(), true); }
/// Numbers >= 0.
inline CLI::Validator nonNegative() { return inRange(0.0, std::numeric_limits<double>::infinity()); }

/// A log's name without its folder and its log extensions (.gz, .clf, .log, .bag, .db3, .mcap): where its
/// ground truth and relations are looked for (STEM.gt.tum, STEM.relations).
inline std::string logStem(const std::string &path) {
  std::filesystem::path p(path);
  while (p.has_extension() && (p.extension() == ".gz" || p.extension() == ".clf" || p.extension() == ".log" ||
                               p.extension() == ".bag" || p.extension() == ".db3" || p.extension() == ".mcap"))
    p = p.stem();
  return p.filename().string();
}

/// The pose X Y YAW (m, m, deg) that option `name` was given, yaw in radians; throws
/// CLI::ValidationError naming the option unless all three are finite.
inline io::Pose2D poseOption(const std::string &name, const std::vector<double> &v) {
  for (double value : v)
    if (!std::isfinite(value)) throw CLI::ValidationError(name, "X Y YAW must be finite numbers");
  return {v[0], v[1], v[2] * M_PI / 180.0};
}

/// --laser-pose X Y YAW: the laser's pose on the robot (m, m, deg), `what` said of it in the help.
inline void addLaserPoseOption(CLI::App &command, std::optional<io::Pose2D> &laser_pose, const std::string &what) {
  command
      .add_option_function<std::vector<double>>(
          "--laser-pose",
          [&laser_pose](const std::vector<double> &v) {
            const io::Pose2D mounting = poseOption("--laser-pose", v);
            if (!io::isMounting(mounting))
              throw CLI::ValidationError("--laser-pose",
                                         "X and Y must lie within 100 m of the robot, YAW within 360 deg");
            laser_pose = mounting;
          },
          "The laser's pose on the robot, base_link -> laser (m, m, deg), " + what)
      ->expected(3)
      ->type_name("X Y YAW");
}

/// An option `name` X Y YAW: a motion, source to target (m, m, deg; kept in radians).
inline CLI::Option *addMotionOption(CLI::App &command, const std::string &name, std::optional<io::Pose2D> &motion,
                                    const std::string &help) {
  return command
      .add_option_function<std::vector<double>>(
          name, [&motion, name](const std::vector<double> &v) { motion = poseOption(name, v); }, help)
      ->expected(3)
      ->type_name("X Y YAW");
}

/// --max-range, --scan-topic, --odom-topic, --no-wheel-odometry, --scan-period, --beam-step, --laser-pose.
inline void addReadOptions(CLI::App &command, io::LogReadOptions &options) {
  command.add_option("--max-range", options.max_range, "Readings at or above are no-return (m, > 0)")
      ->capture_default_str()
      ->check(positive());
  command.add_option("--scan-topic", options.scan_topic,
                     "Bags: sensor_msgs/LaserScan or MultiEchoLaserScan topic (default: the first LaserScan one)");
  command.add_option("--odom-topic", options.odometry_topic, "Bags: nav_msgs/Odometry topic (default: the first)");
  command.add_flag("--wheel-odometry,!--no-wheel-odometry", options.wheel_odometry,
                   "Read the log's wheel odometry (on by default; --no-wheel-odometry: the scans alone, as from a "
                   "LIDAR without wheels; the poses of --log-poses and --guess odom are then missing too)");
  command
      .add_option("--scan-period", options.scan_period,
                  "Scans without beam timing (CARMEN, PCD): s per turn of the LIDAR, beams taken in index order "
                  "from the stamp (s, 0-10; 0: none)")
      ->capture_default_str()
      ->check(inRange(0.0, io::LogReadOptions::kLongestScanPeriod));
  command
      .add_option("--beam-step", options.beam_step,
                  "Keep every N-th beam from the first: the scans of a LIDAR with N times the angular step (>= 1)")
      ->capture_default_str()
      ->check(CLI::Range(std::size_t{1}, std::size_t{1000}));
  addLaserPoseOption(command, options.laser_pose, "over what the log says");
}

/// --frame: the frame `what` (a trajectory, motions) is given in.
inline void addFrameOption(CLI::App &command, std::string &frame, const std::string &what = "the trajectory") {
  command
      .add_option(
          "--frame", frame,
          "Frame of " + what + ": robot (base_link, when the log or --laser-pose gives the laser's mounting) or laser")
      ->check(CLI::IsMember(odometry::frameNames()))
      ->capture_default_str();
}
/// The frame of a name --frame has checked.
inline odometry::Frame frameOf(const std::string &name) { return odometry::frameNamed(name).value(); }

/// Method settings worth studying from the command line; defaults are the library's.
struct MethodOptions {
  double contour_step = 0.05, threshold = 0.08, local_fallback = RegistrationParams{}.local_fallback_min_overlap,
         probe_distance = RegistrationParams{}.probe_distance;
  int candidates = 3, arm_elements = 5;
  bool free_space = RegistrationParams{}.free_space.enabled;
  std::optional<double> icp_max_correspondence;  // unset: each method's tuned value
  double ndt_resolution = 1.0;
  int iterations = 50;

  odometry::MatcherSettings settings() const {
    odometry::MatcherSettings s;
    s.contour.equalization.step = contour_step;
    s.contour.special_points.threshold = threshold;
    s.contour.corner_filter.arm_elements = arm_elements;
    s.registration.correspondence.candidates_per_point = candidates;
    s.registration.local_fallback_min_overlap = local_fallback;
    s.registration.probe_distance = probe_distance;
    s.registration.free_space.enabled = free_space;
    s.icp_max_correspondence = icp_max_correspondence;
    s.icp_iterations = iterations;
    s.ndt_resolution = ndt_resolution;
    return s;
  }
};

inline void addMethodOptions(CLI::App &command, MethodOptions &options) {
  const CLI::Validator fraction = inRange(0.0, 1.0);
  command.add_option("--contour-step", options.contour_step, "Contour: equalized element length (m, 0.001-10)")
      ->capture_default_str()
      ->check(inRange(EqualizationParams::kLeastStep, EqualizationParams::kLongestStep));
  command.add_option("--threshold", options.threshold, "Contour: corner response threshold (0-1]")
      ->capture_default_str()
      ->check(inRange(0.0, 1.0, true));
  command.add_option("--candidates", options.candidates, "Contour: candidate targets per special point (>= 1)")
      ->capture_default_str()
      ->check(inRange(1, 1000));
  command.add_option("--arm", options.arm_elements, "Contour: elements per corner arm (>= 1)")
      ->capture_default_str()
      ->check(inRange(1, 1000));
  command
      .add_option("--local-fallback", options.local_fallback,
                  "Contour: min contour overlap to accept the refined guess when corners cannot decide; three "
                  "quarters of it with the beams of both scans agreeing (0-1, 0: off)")
      ->capture_default_str()
      ->check(fraction);
  command.add_flag("--free-space,!--no-free-space", options.free_space,
                   "Contour: weigh free-space evidence (on by default; --no-free-space: contour fit alone)");
  command
      .add_option("--probe-distance", options.probe_distance,
                  "Contour: a motion of the local fallback or of few corners must settle back when refined from this "
                  "far off along its weakest direction (m, 0: no check)")
      ->capture_default_str()
      ->check(nonNegative());
  command
      .add_option("--icp-max-distance", options.icp_max_correspondence,
                  "ICP/ICP-PL/GICP: max correspondence distance (m, > 0; default: each method's best on the "
                  "relation logs, icp 0.5, icp-pl 0.25, gicp 0.5)")
      ->check(positive());
  command.add_option("--ndt-resolution", options.ndt_resolution, "NDT/NDT2D: cell size (m, >= 0.05)")
      ->capture_default_str()
      ->check(inRange(0.05, 1000.0));
  command.add_option("--iterations", options.iterations, "ICP/ICP-PL/GICP/NDT: max iterations (>= 1)")
      ->capture_default_str()
      ->check(inRange(1, 100000));
}

/// Whether the library accepts the settings `options` make (option checks catch most values
/// first); otherwise a validation error naming what is wrong.
void validateMethodOptions(const MethodOptions &options);

/// Checks before any work that `path` can be written as a file: its folder exists and it is
/// not a folder. Otherwise a validation error naming `option` and the path.
void checkOutputFile(const std::string &option, const std::string &path);

/// Creates the folder `path` (and its parents) before any work; a validation error naming
/// `option` and the path when it cannot (a file of that name exists, no permission).
void prepareOutputFolder(const std::string &option, const std::string &path);

/// --deskew / --no-deskew: scans with beam timing deskewed by the motion over their sweep (deskew.h).
inline void addDeskewOption(CLI::App &command, bool &deskew) {
  command.add_flag("--deskew,!--no-deskew", deskew,
                   "Deskew scans that carry beam timing with the motion over each sweep, by the wheel odometry when "
                   "the log has it (on by default; docs/algorithm.md)");
}

/// --keyframes, --keyframe-distance, --keyframe-angle: match against the last keyframe
/// (odometry.h), a new keyframe after this much motion or turn (the local map's keyframes too).
struct KeyframeOptions {
  bool match_keyframes = false;
  double distance = 0.3;    ///< m
  double angle_deg = 11.5;  ///< deg

  void applyTo(odometry::OdometryOptions &options) const {
    options.keyframes = match_keyframes;
    options.keyframe_distance = distance;
    options.keyframe_angle = angle_deg * M_PI / 180.0;
  }
};

inline void addKeyframeOptions(CLI::App &command, KeyframeOptions &options) {
  command.add_flag("--keyframes", options.match_keyframes, "Match against the last keyframe, not the previous scan");
  command.add_option("--keyframe-distance", options.distance, "New keyframe after this motion (m)")
      ->capture_default_str()
      ->check(nonNegative());
  command.add_option("--keyframe-angle", options.angle_deg, "New keyframe after this turn (deg)")
      ->capture_default_str()
      ->check(nonNegative());
}

/// --local-map: match against a local map of the last N keyframes (odometry.h), 0: off.
inline void addLocalMapOption(CLI::App &command, std::size_t &keyframes) {
  command
      .add_option("--local-map", keyframes,
                  "Match against a local map of the last N keyframes, not the previous scan (0-100, 0: off)")
      ->capture_default_str()
      ->check(inRange(0, 100));
}

/// --guess: where each registration's initial guess comes from.
inline void addGuessOption(CLI::App &command, std::string &guess) {
  command.add_option("--guess", guess, "Initial guess: zero, odom (wheel odometry), velocity")
      ->check(CLI::IsMember(odometry::guessSourceNames()))
      ->capture_default_str();
}
/// The guess source of a name --guess has checked.
inline odometry::GuessSource guessSource(const std::string &name) { return odometry::guessSourceNamed(name).value(); }

/// --wheel-fusion / --no-wheel-fusion and --wheel-noise: the wheel odometry as a prior (wheel_fusion.h).
inline void addWheelFusionOptions(CLI::App &command, bool &fuse, odometry::WheelNoise &noise) {
  command.add_flag("--wheel-fusion,!--no-wheel-fusion", fuse,
                   "Fuse contour registrations with the wheel odometry by covariance: with --guess odom each one, "
                   "with another guess those that leave a direction free; the wheels decide that direction only "
                   "(on by default)");
  command
      .add_option_function<std::vector<double>>(
          "--wheel-noise",
          [&noise](const std::vector<double> &v) {
            noise.rotation_per_rotation = v[0];
            noise.rotation_per_translation = v[1];
            noise.translation_per_translation = v[2];
            noise.translation_per_rotation = v[3];
            std::string why;
            if (!noise.validate(&why)) throw CLI::ValidationError("--wheel-noise", why);
          },
          "The wheels' error model for --wheel-fusion, as AMCL's odom_alpha1-4: rad^2 per rad^2 turned, rad^2 per "
          "m^2 driven, m^2 per m^2 driven, m^2 per rad^2 turned (default 0.07 0.001 0.04 0.0007)")
      ->expected(4)
      ->type_name("A1 A2 A3 A4");
}

/// How the odometry chains registrations, as `odometry` and `compare` take it: --frame, the
/// keyframe options, --local-map, --deskew and the wheel fusion options.
struct ChainOptions {
  std::string frame = "robot";
  KeyframeOptions keyframes;
  std::size_t local_map = 0;
  bool deskew = true, wheel_fusion = true;
  odometry::WheelNoise wheel_noise;

  /// The odometry's options for these, each registration's guess from `guess` (a name --guess has checked).
  odometry::OdometryOptions runOptions(const std::string &guess) const {
    odometry::OdometryOptions options;
    options.guess = guessSource(guess);
    keyframes.applyTo(options);
    options.local_map_keyframes = local_map;
    options.deskew = deskew;
    options.fuse_wheel_odometry = wheel_fusion;
    options.wheel_noise = wheel_noise;
    options.frame = frameOf(frame);
    return options;
  }
};

inline void addChainOptions(CLI::App &command, ChainOptions &options) {
  addFrameOption(command, options.frame);
  addKeyframeOptions(command, options.keyframes);
  addLocalMapOption(command, options.local_map);
  addDeskewOption(command, options.deskew);
  addWheelFusionOptions(command, options.wheel_fusion, options.wheel_noise);
}

/// A converged motion this far from a reference, or a triangle of registrations this far from
/// closing, is a gross error (m, deg): not noise a covariance should cover.
constexpr double kGrossMetres = 0.25, kGrossDegrees = 5.0;

/// Whether motions `metres` and `degrees` apart are grossly apart.
inline bool isGross(double metres, double degrees) { return metres > kGrossMetres || degrees > kGrossDegrees; }

/// Whether a departure from a motion (x, y in m, yaw in rad) is gross.
inline bool isGross(const io::Pose2D &departure) {
  return isGross(std::hypot(departure.x, departure.y), std::abs(departure.yaw) * 180 / M_PI);
}

/// A check that accepts the method names of odometry::methodNames().
inline CLI::IsMember methodCheck() { return CLI::IsMember(odometry::methodNames()); }

/// Prints the reader's warnings (skipped lines, the first few described) to stderr.
void printReadReport(const io::ScanLog &log);

/// One pair of scans of a log, by index in stamp order: the source `scan` onto the target `to`.
struct ScanPair {
  std::string input;
  int scan = 1, to = -1;  ///< `to` < 0: the scan before `scan`
  int target() const { return to >= 0 ? to : scan - 1; }
};

/// The input, --scan (`scan_help`) and --to options.
void addScanPairOptions(CLI::App &command, ScanPair &pair, const std::string &scan_help);

/// Throws CLI::ValidationError for scan 0 without --to: it has no scan before it.
void checkScanPair(const ScanPair &pair);

/// Reads the pair's log (its warnings to stderr, as printReadReport). False, with the error on
/// stderr naming the log and its scans, when the log has no such scans.
bool readScanPair(const ScanPair &pair, const io::LogReadOptions &read, io::ScanLog &log);

/// A pair's true motion, when known, for the commands that answer one pair (`debug`,
/// `register`): --reference X Y YAW, --log-poses or --gt FILE, at most one of them.
struct ReferenceOptions {
  std::optional<io::Pose2D> motion;  ///< --reference, in the frame of the command's --frame (yaw in rad)
  bool log_poses = false;            ///< --log-poses: from the log's own poses
  std::string ground_truth;          ///< --gt: from this TUM trajectory at the scans' stamps
  /// Whether the reference comes from poses (--log-poses or --gt) rather than --reference.
  bool fromPoses() const { return log_poses || !ground_truth.empty(); }
};
/// --reference (`reference_help` says what the command does with it), --log-poses and --gt,
/// each excluding the others.
void addReferenceOptions(CLI::App &command, ReferenceOptions &options, const std::string &reference_help);
/// The robot's motion from the pair's target scan to its source scan by the poses --log-poses or
/// --gt name (options.fromPoses()). None, with the error on stderr naming where the poses came
/// from, when there is no pose at either scan or the ground truth's stamps do not increase.
std::optional<io::Pose2D> referenceFromPoses(const ReferenceOptions &options, const ScanPair &pair,
                                             const io::ScanLog &log);

/// --reference-sigma M DEG: the reference's own error, added to each covariance for the NEES
/// (`sigma` holds its default; `nees_of` says where the NEES is printed).
inline void addReferenceSigmaOption(CLI::App &command, std::vector<double> &sigma, const std::string &nees_of) {
  command
      .add_option("--reference-sigma", sigma,
                  "The reference's own error, added to each covariance for " + nees_of +
                      " (m, deg; 0.05 1 suits the Radish logs' corrected poses, 0.02 0.5 the Kümmerle relations)")
      ->expected(2)
      ->capture_default_str()
      ->check(nonNegative());
}

/// How far apart two motions are: translation (m) and rotation (deg, the yaw difference wrapped).
struct Apart {
  double metres = 0.0, degrees = 0.0;
};
Apart apart(const Eigen::Matrix3d &a, const Eigen::Matrix3d &b);

/// The motions and covariances of `result`, found in the laser's frame (the transform, the
/// rejected motion, the alternatives), as the robot's, the laser mounted at `mounting`.
void toRobotFrame(odometry::MatchResult &result, const io::Pose2D &mounting);

/// " (one beam in N)" when the log was read with --beam-step N > 1, else "": for the headers of
/// tables, so that saved output says which scans it measured.
std::string beamsRead(const io::LogReadOptions &read);

/// The motion over scan k's sweep, by the wheel odometry, as the odometry deskews it: none when
/// `deskew` is off or the scan carries no beam timing. `usual_interval`: the log's
/// odometry::medianScanInterval, computed once per log.
inline SweepMotion sweepToDeskew(const io::ScanLog &log, std::size_t k, bool deskew, double usual_interval) {
  const bool timed = deskew && log.entries[k].scan.time_increment > 0.0;
  return timed ? odometry::wheelMotionOverSweep(log, k, usual_interval).value_or(SweepMotion{}) : SweepMotion{};
}

/// printf into a string.
std::string printed(const char *format, ...) __attribute__((format(printf, 1, 2)));

/// With the guess "odom", warns on stderr of scans of `log` without wheel odometry: their
/// registrations start from no motion.
void warnOfMissingOdometry(const io::ScanLog &log, const std::string &guess, const io::LogReadOptions &read);

/// Why a trajectory whose `count` of `poses` stamps are no later than the one before gets no
/// metric (evaluation::nonIncreasingStamps; `which`: "" or "ground-truth "), to follow "FILE: ".
std::string stampsDoNotIncrease(std::size_t count, std::size_t poses, const char *which);

/// The TUM ground truth `path`'s poses at the stamps of `log`'s scans, interpolated as
/// `evaluate` does (evaluation::poseAt; none where it has no pose). None, with `why` ("PATH:
/// ..."), when its stamps do not increase: a relations file read as a trajectory repeats its
/// first stamps with other motions.
std::optional<std::vector<std::optional<io::Pose2D>>> groundTruthAtScans(const std::string &path,
                                                                         const io::ScanLog &log, std::string &why);

using evaluation::percentile;

}  // namespace contour_reg::cli

namespace contour_reg::cli {

/// A one-line progress bar on stderr when stderr is a terminal; silent otherwise.
class ProgressBar {
 public:
  explicit ProgressBar(std::string label);
  ~ProgressBar();
  void operator()(std::size_t done, std::size_t total);
  /// Ends the bar's line (when one was drawn); the next call starts a new bar.
  void finish();

 private:
  std::string label_;
  bool enabled_;
  int shown_ = -1;
};

}  // namespace contour_reg::cli
