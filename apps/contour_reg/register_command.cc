// contour_reg register: one pair of scans, each method's answer as YAML on stdout.
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <pcl/console/print.h>

#include "cli_options.h"
#include "commands.h"
#include "contour_reg/evaluation/metrics.h"
#include "contour_reg/io/pose2d.h"

namespace contour_reg::cli {

namespace {

struct RegisterOptions {
  ScanPair pair;
  std::vector<std::string> methods{"contour"};
  std::optional<io::Pose2D> guess;  // in `frame`; none: no motion
  ReferenceOptions reference;
  std::vector<double> reference_sigma{0.0, 0.0};  // m, deg: the reference's own error, for the NEES
  std::string frame = "robot";
  io::LogReadOptions read;
  MethodOptions method_options;
};

// A motion as a YAML flow map: x, y in m, yaw in deg.
std::string motionYaml(const Eigen::Matrix3d &motion) {
  const io::Pose2D pose = io::toPose(motion);
  char text[128];
  std::snprintf(text, sizeof text, "{x_m: %.4f, y_m: %.4f, yaw_deg: %.3f}", pose.x, pose.y, pose.yaw * 180.0 / M_PI);
  return text;
}

// A string as a YAML double-quoted scalar.
std::string quoted(const std::string &text) {
  std::string out = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

// How far `motion` lies from the reference, as a YAML flow map (m, deg).
std::string errorYaml(const Eigen::Matrix3d &motion, const io::Pose2D &reference) {
  const Apart error = apart(motion, io::toMatrix(reference));
  char text[64];
  std::snprintf(text, sizeof text, "{m: %.4f, deg: %.3f}", error.metres, error.degrees);
  return text;
}

// How far a converged answer lies from the reference and, with a covariance, its normalised
// error squared with the reference's own error added (`sigma`: m, deg).
void printError(const odometry::MatchResult &r, const io::Pose2D &reference, const std::vector<double> &sigma) {
  std::printf("  error: %s\n", errorYaml(r.transform, reference).c_str());
  if (!r.covariance.isZero())
    std::printf("  nees: %.3f\n", evaluation::normalisedErrorSquared(io::toPose(r.transform), reference, r.covariance,
                                                                     sigma[0], sigma[1] * M_PI / 180.0));
}

void printResult(const std::string &method, const odometry::MatchResult &r, const std::optional<io::Pose2D> &reference,
                 const std::vector<double> &sigma) {
  std::printf("- method: %s\n", method.c_str());
  std::printf("  status: %s\n", r.converged ? "converged" : r.status.c_str());
  // A method that did not converge vouches for no motion: what it weighed is `declined`.
  if (r.converged) {
    std::printf("  motion: %s\n", motionYaml(r.transform).c_str());
    if (!r.covariance.isZero()) {
      const Eigen::Matrix3d &c = r.covariance;
      std::printf("  covariance: [%.4e, %.4e, %.4e, %.4e, %.4e, %.4e, %.4e, %.4e, %.4e]\n", c(0, 0), c(0, 1), c(0, 2),
                  c(1, 0), c(1, 1), c(1, 2), c(2, 0), c(2, 1), c(2, 2));
    }
    if (reference) printError(r, *reference, sigma);
    if (r.overlap) std::printf("  overlap: %.3f\n", *r.overlap);
    if (r.score) std::printf("  score: %.3f\n", *r.score);
  } else {
    std::printf("  reason: %s\n", quoted(r.reason).c_str());
  }
  if (r.rejected) {
    const char *kind = r.converged ? "rival" : "declined";
    std::printf("  %s: %s\n", kind, motionYaml(*r.rejected).c_str());
    if (reference) std::printf("  %s_error: %s\n", kind, errorYaml(*r.rejected, *reference).c_str());
  }
  if (!r.alternatives.empty()) {
    std::printf("  alternatives:\n");
    for (const RejectedMotion &alternative : r.alternatives)
      std::printf("    - %s\n", motionYaml(alternative.transform).c_str());
  }
  std::printf("  milliseconds: %.3f\n", r.milliseconds);
}

int runRegister(const RegisterOptions &options) {
  pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
  io::ScanLog log;
  if (!readScanPair(options.pair, options.read, log)) return 2;
  const ScanPair &pair = options.pair;
  const LaserScan &source = log.entries[std::size_t(pair.scan)].scan,
                  &target = log.entries[std::size_t(pair.target())].scan;
  // The registration runs in the laser's frame; with the log's mounting, the guess and the
  // answers are the robot's.
  const std::optional<io::Pose2D> mounting = options.frame == "robot" ? log.laser_pose : std::nullopt;
  io::Pose2D guess = options.guess.value_or(io::Pose2D{});
  if (mounting) guess = io::laserMotion(guess, *mounting);
  // The reference as the answers are given: --reference in --frame, the poses' as the robot's.
  std::optional<io::Pose2D> reference = options.reference.motion;
  if (options.reference.fromPoses()) {
    reference = referenceFromPoses(options.reference, pair, log);
    if (!reference) return 1;
    if (!mounting && log.laser_pose) reference = io::laserMotion(*reference, *log.laser_pose);
  }
  std::printf("# scan %d (source, stamp %.6f s) onto scan %d (target, stamp %.6f s) of %s\n", pair.scan, source.stamp,
              pair.target(), target.stamp, pair.input.c_str());
  std::printf(
      "# motions and covariances in %s; motion: the source scan's pose in the target scan's frame (x m, y m, "
      "yaw deg); covariance: row-major x m, y m, yaw rad\n",
      odometry::frameDescription(mounting ? odometry::Frame::kRobot : odometry::Frame::kLaser, log).c_str());
  if (reference)
    std::printf(
        "# reference: %s; error (rival_error, declined_error): each answer's (each motion weighed and not "
        "taken) distance from it (m, deg), nees: its normalised error squared "
        "under the answer's covariance plus %g m / %g deg for the reference's own error (3 on average for an "
        "honest covariance, above %.2f outside its 99 %% ellipsoid)\n",
        motionYaml(io::toMatrix(*reference)).c_str(), options.reference_sigma[0], options.reference_sigma[1],
        evaluation::kNees99);
  const odometry::MatcherSettings settings = options.method_options.settings();
  for (const std::string &method : options.methods) {
    std::unique_ptr<odometry::ScanMatcher> matcher = odometry::makeScanMatcher(method, settings);
    odometry::MatchResult result = matcher->match(target, source, io::toMatrix(guess));
    if (mounting) toRobotFrame(result, *mounting);
    printResult(method, result, reference, options.reference_sigma);
  }
  return 0;
}

}  // namespace

void addRegisterCommand(CLI::App &app) {
  auto options = std::make_shared<RegisterOptions>();
  CLI::App *command = app.add_subcommand(
      "register", "Register one scan onto another: each method's motion, status and covariance as YAML");
  addScanPairOptions(*command, options->pair, "Source scan of the pair (index in stamp order)");
  command->add_option("--methods", options->methods, "Methods to run, each on the same pair")
      ->capture_default_str()
      ->check(methodCheck());
  addMotionOption(*command, "--guess", options->guess,
                  "Initial guess of the motion, in the frame of --frame (m, m, deg; default: none)");
  addReferenceOptions(*command, options->reference,
                      "The pair's true motion, when known, in the frame of --frame (m, m, deg): each converged answer "
                      "says how far it lies from it and, with a covariance, its NEES");
  addReferenceSigmaOption(*command, options->reference_sigma, "each answer's NEES");
  addFrameOption(*command, options->frame, "the motions, covariances, guess and reference");
  addReadOptions(*command, options->read);
  addMethodOptions(*command, options->method_options);
  command->callback([options]() {
    checkScanPair(options->pair);
    validateMethodOptions(options->method_options);
    runCommand([&] { return runRegister(*options); });
  });
}

}  // namespace contour_reg::cli
