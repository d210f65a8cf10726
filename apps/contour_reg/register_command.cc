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
#include "contour_reg/io/pose2d.h"

namespace contour_reg::cli {

namespace {

struct RegisterOptions {
  ScanPair pair;
  std::vector<std::string> methods{"contour"};
  std::optional<io::Pose2D> guess;  // in `frame`; none: no motion
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

void printResult(const std::string &method, const odometry::MatchResult &r) {
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
    if (r.overlap) std::printf("  overlap: %.3f\n", *r.overlap);
    if (r.score) std::printf("  score: %.3f\n", *r.score);
  } else {
    std::printf("  reason: %s\n", quoted(r.reason).c_str());
  }
  if (r.rejected) std::printf("  %s: %s\n", r.converged ? "rival" : "declined", motionYaml(*r.rejected).c_str());
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
  std::printf("# scan %d (source, stamp %.6f s) onto scan %d (target, stamp %.6f s) of %s\n", pair.scan, source.stamp,
              pair.target(), target.stamp, pair.input.c_str());
  std::printf(
      "# motions and covariances in %s; motion: the source scan's pose in the target scan's frame (x m, y m, "
      "yaw deg); covariance: row-major x m, y m, yaw rad\n",
      odometry::frameDescription(mounting ? odometry::Frame::kRobot : odometry::Frame::kLaser, log).c_str());
  const odometry::MatcherSettings settings = options.method_options.settings();
  for (const std::string &method : options.methods) {
    std::unique_ptr<odometry::ScanMatcher> matcher = odometry::makeScanMatcher(method, settings);
    odometry::MatchResult result = matcher->match(target, source, io::toMatrix(guess));
    if (mounting) toRobotFrame(result, *mounting);
    printResult(method, result);
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
  addFrameOption(*command, options->frame, "the motions, covariances and guess");
  addReadOptions(*command, options->read);
  addMethodOptions(*command, options->method_options);
  command->callback([options]() {
    checkScanPair(options->pair);
    validateMethodOptions(options->method_options);
    runCommand([&] { return runRegister(*options); });
  });
}

}  // namespace contour_reg::cli
