// contour_reg closure: checks a method's covariance on a log without any reference, by
// closing triangles of registrations (scans k -> k + 1 -> k + 2 against k -> k + 2).
#include <cmath>
#include <cstdio>
#include <memory>
#include <numeric>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <pcl/console/print.h>

#include "cli_options.h"
#include "commands.h"
#include "contour_reg/evaluation/closure.h"
#include "contour_reg/evaluation/metrics.h"
#include "contour_reg/io/pose2d.h"
#include "contour_reg/io/read_log.h"
#include "contour_reg/odometry/odometry.h"
#include "contour_reg/odometry/scan_matcher.h"

namespace contour_reg::cli {

namespace {

struct ClosureOptions {
  std::string input;
  std::vector<std::string> methods = {"contour"};
  std::size_t limit = 0;
  std::string triangles_csv;  // one row per triangle and method, when set
  bool log_poses = false;     // also weigh each k -> k + 1 registration against the log's own poses
  bool deskew = true;
  io::LogReadOptions read;
  MethodOptions method_options;
};

// The motion of scan k + 1 onto scan k by the log's own poses, in the laser's frame as the
// registrations are; none where a pose is missing.
std::optional<io::Pose2D> logMotion(const io::ScanLog &log, std::size_t k) {
  const std::optional<io::Pose2D> &a = log.entries[k].odometry, &b = log.entries[k + 1].odometry;
  if (!a || !b) return std::nullopt;
  const io::Pose2D motion = io::between(*a, *b);
  return log.laser_pose ? io::laserMotion(motion, *log.laser_pose) : motion;
}

int runClosure(const ClosureOptions &options) {
  pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
  const io::ScanLog log = io::readLog(options.input, options.read);
  printReadReport(log);
  std::size_t triangles = log.entries.size() >= 3 ? log.entries.size() - 2 : 0;
  if (options.limit > 0) triangles = std::min(triangles, options.limit);
  if (triangles == 0) {
    std::fprintf(stderr, "error: no triangle: %s has %zu scans, need 3\n", options.input.c_str(), log.entries.size());
    return 1;
  }
  std::printf(
      "%s%s: %zu triangles of scans k, k + 1, k + 2 (k -> k + 2 against k -> k + 1 -> k + 2), zero guess, "
      "no reference\n\n",
      options.input.c_str(), beamsRead(options.read).c_str(), triangles);
  std::FILE *csv = nullptr;
  if (!options.triangles_csv.empty()) {
    csv = std::fopen(options.triangles_csv.c_str(), "w");
    if (!csv) throw std::runtime_error("cannot write " + options.triangles_csv);
    std::fprintf(csv, "method,k,error_x_m,error_y_m,error_yaw_rad,nees,nees_translation,nees_yaw\n");
  }
  std::printf(
      "| method | triangles closed | gross closures (> 25 cm or 5 deg) | mean NEES | NEES > %.2f (outside the 99 %% "
      "ellipsoid) | translation NEES > 9.21 | yaw NEES > 6.63 |\n",
      evaluation::kNees99);
  std::printf("|---|---|---|---|---|---|---|\n");
  std::vector<std::string> pose_rows;  // with --log-poses, one per method
  const double usual_interval = odometry::medianScanInterval(log);
  const auto sweep = [&](std::size_t k) { return sweepToDeskew(log, k, options.deskew, usual_interval); };
  for (const std::string &name : options.methods) {
    auto matcher = odometry::makeScanMatcher(name, options.method_options.settings());
    const auto match = [&](std::size_t first, std::size_t second) {
      return matcher->match(log.entries[first].scan, log.entries[second].scan, Eigen::Matrix3d::Identity(),
                            sweep(first), sweep(second));
    };
    ProgressBar progress(name);
    std::size_t closed = 0, gross = 0, outside = 0, outside_translation = 0, outside_yaw = 0, with_covariance = 0;
    std::vector<double> nees;
    // Against the log's poses, per registration k -> k + 1 (the triangles' legs): whether it
    // converged far off the poses, and whether a triangle through it (k - 1 or k) closed
    // within its ellipsoid.
    std::vector<char> off_poses(triangles + 1, 0), in_closing_triangle(triangles + 1, 0);
    std::size_t against_poses = 0;
    const auto weighLeg = [&](std::size_t k, const odometry::MatchResult &leg) {
      const std::optional<io::Pose2D> motion = options.log_poses ? logMotion(log, k) : std::nullopt;
      if (!leg.converged || !motion) return;
      ++against_poses;
      off_poses[k] = isGross(io::between(*motion, io::toPose(leg.transform)));
    };
    odometry::MatchResult next = match(0, 1);  // k + 1 -> k + 2 of one triangle is k -> k + 1 of the next
    weighLeg(0, next);
    for (std::size_t k = 0; k < triangles; ++k) {
      progress(k, triangles);
      const odometry::MatchResult ab = std::move(next);
      next = match(k + 1, k + 2);
      const odometry::MatchResult &bc = next;
      weighLeg(k + 1, bc);
      if (!ab.converged || !bc.converged) continue;
      const odometry::MatchResult ac = match(k, k + 2);
      if (!ac.converged) continue;
      ++closed;
      const evaluation::TriangleClosure closure =
          evaluation::triangleClosure(io::toPose(ab.transform), ab.covariance, io::toPose(bc.transform), bc.covariance,
                                      io::toPose(ac.transform), ac.covariance);
      const bool gross_closure = isGross({closure.error(0), closure.error(1), closure.error(2)});
      gross += gross_closure;
      const bool covariance = !ab.covariance.isZero() && !bc.covariance.isZero() && !ac.covariance.isZero();
      double translation = 0.0, yaw = 0.0;
      if (covariance && !gross_closure) {
        ++with_covariance;
        nees.push_back(closure.nees);
        const Eigen::Vector2d e = closure.error.head<2>();
        translation = e.dot(closure.covariance.topLeftCorner<2, 2>().ldlt().solve(e));
        yaw = closure.error(2) * closure.error(2) / closure.covariance(2, 2);
        outside += closure.nees > evaluation::kNees99;
        outside_translation += translation > 9.21;  // chi-square, 2 degrees of freedom, 99 %
        outside_yaw += yaw > 6.63;                  // 1 degree of freedom
        if (closure.nees <= evaluation::kNees99) in_closing_triangle[k] = in_closing_triangle[k + 1] = 1;
      }
      if (csv)
        std::fprintf(csv, "%s,%zu,%.5f,%.5f,%.6f,%.4g,%.4g,%.4g\n", name.c_str(), k, closure.error(0), closure.error(1),
                     closure.error(2), covariance ? closure.nees : 0.0, translation, yaw);
    }
    progress.finish();
    std::size_t off = 0, off_but_closing = 0;
    for (std::size_t k = 0; k <= triangles; ++k) {
      off += off_poses[k];
      off_but_closing += off_poses[k] && in_closing_triangle[k];
    }
    if (options.log_poses)
      pose_rows.push_back(printed("| %s | %zu | %zu | %s |", name.c_str(), against_poses, off,
                                  with_covariance ? std::to_string(off_but_closing).c_str() : "-"));
    const auto percent = [&](std::size_t count) {
      return with_covariance
                 ? printed("%.1f %%", 100.0 * static_cast<double>(count) / static_cast<double>(with_covariance))
                 : std::string("-");
    };
    const std::string mean =
        nees.empty() ? "-" : printed("%.2f", std::accumulate(nees.begin(), nees.end(), 0.0) / nees.size());
    std::printf("| %s | %zu of %zu | %zu | %s | %s | %s | %s |\n", name.c_str(), closed, triangles, gross, mean.c_str(),
                percent(outside).c_str(), percent(outside_translation).c_str(), percent(outside_yaw).c_str());
    std::fflush(stdout);
  }
  std::printf(
      "\nNEES over the closed triangles that are not gross, of the composition's departure from the identity "
      "weighed by the three covariances; an honest covariance gives a mean of 3 and 1 %% outside. The three "
      "registrations share scans, whose own noise largely cancels around a triangle: a share above 1 %% shows "
      "an over-confident covariance, one below it says less. A method without a covariance shows '-'.\n");
  if (options.log_poses) {
    std::printf(
        "\nAgainst the log's own poses (registrations k -> k + 1 that converged, where the log has both poses):\n\n"
        "| method | registrations | more than 25 cm or 5 deg off the poses | of those, in a triangle that closes "
        "within its 99 %% ellipsoid |\n|---|---|---|---|\n");
    for (const std::string &row : pose_rows) std::printf("%s\n", row.c_str());
    std::printf(
        "\nA registration far off the poses whose triangle closes agrees with the two registrations around it: "
        "there the poses are off, or all three registrations alike (along repeated structure).\n");
  }
  if (csv) std::fclose(csv);
  return 0;
}

}  // namespace

void addClosureCommand(CLI::App &app) {
  auto options = std::make_shared<ClosureOptions>();
  CLI::App *command = app.add_subcommand(
      "closure",
      "Check the covariance on a log without a reference: register scans k -> k + 1, k + 1 -> k + 2 and "
      "k -> k + 2 from a zero guess and weigh how far they fail to compose");
  command->add_option("input", options->input, "CARMEN log, ROS 1 or ROS 2 bag or PCD folder")
      ->required()
      ->check(CLI::ExistingPath);
  command->add_option("--methods", options->methods, "Methods to run")->check(methodCheck())->capture_default_str();
  addReadOptions(*command, options->read);
  addMethodOptions(*command, options->method_options);
  command->add_option("--triangles-csv", options->triangles_csv,
                      "Write one row per closed triangle and method to this CSV file");
  command->add_flag("--log-poses", options->log_poses,
                    "Also weigh each k -> k + 1 registration against the log's own poses (the corrected poses of the "
                    "Radish logs): how many are more than 25 cm or 5 deg off, and of those, how many lie in a "
                    "triangle that closes");
  command->add_option("--limit", options->limit, "At most this many triangles (0: all)")->capture_default_str();
  addDeskewOption(*command, options->deskew);
  command->callback([options]() {
    validateMethodOptions(options->method_options);
    if (!options->triangles_csv.empty()) checkOutputFile("--triangles-csv", options->triangles_csv);
    runCommand([&] { return runClosure(*options); });
  });
}

}  // namespace contour_reg::cli
