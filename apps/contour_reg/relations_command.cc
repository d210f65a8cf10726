// contour_reg relations: registers the scan pairs of a relations file from a zero guess
// with several methods and reports how many each recovers, and how fast.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>

#include <pcl/console/print.h>

#include "cli_options.h"
#include "commands.h"
#include "contour_reg/io/read_log.h"
#include "contour_reg/io/trajectory.h"
#include "contour_reg/odometry/scan_matcher.h"

namespace contour_reg::cli {

namespace {

struct RelationsOptions {
  std::string input, relations;
  std::vector<std::string> methods = {"contour", "contour+icp", "icp", "ndt2d"};
  double max_dt = 5.0, tolerance = 0.10, tolerance_deg = 2.0;
  std::size_t limit = 0;
  io::LogReadOptions read;
  MethodOptions method_options;
};

std::size_t nearestScan(const io::ScanLog &log, double stamp) {
  auto it = std::lower_bound(log.entries.begin(), log.entries.end(), stamp,
                             [](const io::LogEntry &e, double t) { return e.scan.stamp < t; });
  std::size_t k = static_cast<std::size_t>(it - log.entries.begin());
  if (k == log.entries.size() || (k > 0 && stamp - log.entries[k - 1].scan.stamp < it->scan.stamp - stamp)) --k;
  return k;
}

int runRelations(const RelationsOptions &options) {
  // PCL's classes print a line per failed pair; the table counts them instead.
  pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
  const io::ScanLog log = io::readLog(options.input, options.read);
  printReadReport(log);
  std::vector<io::Relation> relations;
  for (const io::Relation &r : io::readRelations(options.relations))
    if (std::abs(r.t2 - r.t1) <= options.max_dt) relations.push_back(r);
  if (options.limit > 0 && relations.size() > options.limit) relations.resize(options.limit);
  std::printf("%s: %zu relations with |t2 - t1| <= %.1f s, zero guess, success = within %.2f m and %.1f deg\n\n",
              options.input.c_str(), relations.size(), options.max_dt, options.tolerance, options.tolerance_deg);
  std::printf("| method | recovered | converged | converged but wrong | mean err m (recovered) | median ms | p95 ms |\n");
  std::printf("|---|---|---|---|---|---|---|\n");
  for (const std::string &name : options.methods) {
    auto matcher = odometry::makeScanMatcher(name, options.method_options.settings());
    std::map<std::string, int> reasons;
    std::size_t recovered = 0, converged = 0, wrong = 0;
    double error_sum = 0.0;
    std::vector<double> ms;
    for (const io::Relation &r : relations) {
      const LaserScan &a = log.entries[nearestScan(log, r.t1)].scan, &b = log.entries[nearestScan(log, r.t2)].scan;
      const odometry::MatchResult match = matcher->match(a, b);
      ms.push_back(match.milliseconds);
      const Eigen::Matrix3d &t = match.transform;
      const double et = std::hypot(t(0, 2) - r.motion.x, t(1, 2) - r.motion.y);
      const double er = std::abs(std::remainder(std::atan2(t(1, 0), t(0, 0)) - r.motion.yaw, 2 * M_PI)) * 180 / M_PI;
      const bool ok = et <= options.tolerance && er <= options.tolerance_deg;
      converged += match.converged;
      if (!match.converged) ++reasons[match.status];
      wrong += match.converged && !ok;
      if (match.converged && ok) {
        ++recovered;
        error_sum += et;
      }
    }
    const double n = std::max<double>(1.0, relations.size());
    std::printf("| %s | %.1f %% | %.1f %% | %.1f %% | %.3f | %.3f | %.3f |\n", name.c_str(), 100 * recovered / n,
                100 * converged / n, 100 * wrong / n, recovered ? error_sum / recovered : 0.0, percentile(ms, 0.5),
                percentile(ms, 0.95));
    for (const auto &[reason, count] : reasons) std::fprintf(stderr, "  %s failed: %s: %d\n", name.c_str(), reason.c_str(), count);
    std::fflush(stdout);
  }
  return 0;
}

}  // namespace

void addRelationsCommand(CLI::App &app) {
  auto options = std::make_shared<RelationsOptions>();
  CLI::App *command = app.add_subcommand("relations", "Register the scan pairs of a relations file from a zero guess");
  command->add_option("input", options->input, "CARMEN log, ROS bag or PCD folder")->required();
  command->add_option("--relations", options->relations, "Kuemmerle et al. relations file")->required()->check(CLI::ExistingFile);
  command->add_option("--methods", options->methods, "Methods to run")->check(methodCheck())->capture_default_str();
  command->add_option("--max-dt", options->max_dt, "Only relations at most this far apart (s)")->capture_default_str();
  addReadOptions(*command, options->read);
  addMethodOptions(*command, options->method_options);
  command->add_option("--limit", options->limit, "At most this many relations (0: all)")->capture_default_str();
  command->callback([options]() { runCommand([&] { return runRelations(*options); }); });
}

}  // namespace contour_reg::cli
