// contour_reg odometry: a trajectory by chaining scan registrations of one method.
#include <cstdio>
#include <filesystem>
#include <memory>

#include <pcl/console/print.h>

#include "cli_options.h"
#include "commands.h"
#include "contour_reg/io/pose2d.h"
#include "contour_reg/io/read_log.h"
#include "contour_reg/io/trajectory.h"
#include "contour_reg/odometry/odometry.h"
#include "debug_dump.h"

namespace contour_reg::cli {

namespace {

struct OdometryCommandOptions {
  std::string input, output, method = "contour", guess = "zero";
  bool odom_guess = false;
  ChainOptions chain;
  std::string debug_dir, covariance;
  std::size_t debug_every = 0;
  io::LogReadOptions read;
  MethodOptions methods;
};

// One row per registration: the motion as chained and its covariance (README, the command-line tool).
void writeSteps(const std::string &path, const io::ScanLog &log, const odometry::OdometryRun &run) {
  std::FILE *file = std::fopen(path.c_str(), "w");
  if (!file) throw io::ReadError(path + ": cannot write");
  std::fprintf(file,
               "reference_stamp_s,stamp_s,converged,status,dx_m,dy_m,dyaw_rad,cov_xx_m2,cov_xy_m2,cov_xyaw_m_rad,"
               "cov_yy_m2,cov_yyaw_m_rad,cov_yawyaw_rad2\n");
  for (const odometry::OdometryStep &s : run.steps) {
    const Eigen::Matrix3d &c = s.covariance;
    std::fprintf(file, "%.6f,%.6f,%d,%s,%.6f,%.6f,%.7f,%.6e,%.6e,%.6e,%.6e,%.6e,%.6e\n",
                 log.entries[s.reference].scan.stamp, log.entries[s.scan].scan.stamp, s.converged ? 1 : 0,
                 s.converged ? "converged" : s.status.c_str(), s.motion.x, s.motion.y, s.motion.yaw, c(0, 0), c(0, 1),
                 c(0, 2), c(1, 1), c(1, 2), c(2, 2));
  }
  std::fclose(file);
}

int runOdometryCommand(const OdometryCommandOptions &options) {
  pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
  const io::ScanLog log = io::readLog(options.input, options.read);
  printReadReport(log);
  warnOfMissingOdometry(log, options.odom_guess ? "odom" : options.guess, options.read);
  auto matcher = odometry::makeScanMatcher(options.method, options.methods.settings());
  odometry::OdometryOptions run_options = options.chain.runOptions(options.odom_guess ? "odom" : options.guess);
  ProgressBar progress(options.method);
  run_options.progress = [&](std::size_t done, std::size_t total) { progress(done, total); };
  // Debug images: every N-th pair and every failed registration.
  std::unique_ptr<DebugDumper> dumper;
  if (!options.debug_dir.empty()) {
    dumper = std::make_unique<DebugDumper>(options.debug_dir, options.methods.settings());
    run_options.on_match = [&](std::size_t reference, std::size_t k, const LaserScan &target,
                               const odometry::MatchResult &match, const Eigen::Matrix3d &guess) {
      if (!match.converged || (options.debug_every > 0 && k % options.debug_every == 0)) {
        const PairMotions from_guess{io::toPose(guess), std::nullopt};
        if (options.chain.local_map > 0)
          dumper->dumpMapPair(log, target, reference, k, from_guess);
        else
          dumper->dumpPair(log, reference, k, {}, from_guess);
      }
    };
  }
  const odometry::OdometryRun run = odometry::runOdometry(log, *matcher, run_options);
  progress.finish();
  const std::string frame = odometry::frameDescription(run.frame, log);
  io::writeTum(options.output, run.trajectory, frame);
  if (!options.covariance.empty()) writeSteps(options.covariance, log, run);
  std::printf("%s: %zu scans, %zu registrations by %s, %zu failed (%zu degenerate), median %.3f ms, p95 %.3f ms\n",
              options.input.c_str(), log.entries.size(), run.stats.registrations, options.method.c_str(),
              run.stats.failures, run.stats.degenerate, percentile(run.stats.milliseconds, 0.5),
              percentile(run.stats.milliseconds, 0.95));
  if (run.stats.fused > 0)
    std::printf("  fused with the wheel odometry: %zu (%zu where the scans left a direction free)\n", run.stats.fused,
                run.stats.pinned_by_wheels);
  if (run.stats.recovered_by_retry > 0)
    std::printf("  declined, then converged on a retry (from the prediction, or the scan as taken): %zu\n",
                run.stats.recovered_by_retry);
  if (run.stats.decided_by_prediction > 0)
    std::printf("  ambiguous, decided by the predicted motion: %zu\n", run.stats.decided_by_prediction);
  for (const auto &[reason, count] : run.stats.failure_reasons)
    std::printf("  failed: %s: %zu\n", reason.c_str(), count);
  std::printf("trajectory: %s (%s)\n", options.output.c_str(), frame.c_str());
  return 0;
}

}  // namespace

void addOdometryCommand(CLI::App &app) {
  auto options = std::make_shared<OdometryCommandOptions>();
  CLI::App *command = app.add_subcommand("odometry", "Laser odometry: chain scan registrations into a TUM trajectory");
  command
      ->add_option("input", options->input,
                   "CARMEN log, ROS 1 bag (.bag), ROS 2 bag (folder, .db3 or .mcap) or folder of PCD scans")
      ->required()
      ->check(CLI::ExistingPath);
  command->add_option("--method,-m", options->method, "Registration method")
      ->check(methodCheck())
      ->capture_default_str();
  command->add_option("--output,-o", options->output, "TUM trajectory to write")->required();
  addGuessOption(*command, options->guess);
  command->add_flag("--odom-guess", options->odom_guess, "Same as --guess odom");
  addChainOptions(*command, options->chain);
  command->add_option("--debug-dir", options->debug_dir, "Write debug images of failed registrations here");
  command->add_option("--covariance", options->covariance,
                      "Also write one CSV row per registration: the motion as chained and its covariance (x, y, "
                      "yaw; zero for failures and methods without one)");
  command
      ->add_option("--debug-every", options->debug_every, "With --debug-dir, also every N-th pair (0: failures only)")
      ->capture_default_str();
  addReadOptions(*command, options->read);
  addMethodOptions(*command, options->methods);
  command->callback([options]() {
    validateMethodOptions(options->methods);
    checkOutputFile("--output", options->output);
    if (!options->covariance.empty()) checkOutputFile("--covariance", options->covariance);
    if (!options->debug_dir.empty()) prepareOutputFolder("--debug-dir", options->debug_dir);
    runCommand([&] { return runOdometryCommand(*options); });
  });
}

}  // namespace contour_reg::cli
