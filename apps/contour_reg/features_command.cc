// contour_reg features: the special points of scans of a log.
#include <cmath>
#include <cstdio>
#include <memory>

#include "cli_options.h"
#include "commands.h"
#include "contour_reg/core/contour_features.h"
#include "contour_reg/io/read_log.h"

namespace contour_reg::cli {

namespace {

struct FeaturesOptions {
  std::string input;
  int scan = 0;
  bool all = false;
  io::LogReadOptions read;
  MethodOptions method_options;
};

int runFeatures(const FeaturesOptions &options) {
  const io::ScanLog log = io::readLog(options.input, options.read);
  printReadReport(log);
  const int count = static_cast<int>(log.entries.size());
  if (!options.all && options.scan >= count) {
    std::fprintf(stderr, "error: --scan %d: %s has scans 0..%d\n", options.scan, options.input.c_str(), count - 1);
    return 2;
  }
  const int first = options.all ? 0 : options.scan, last = options.all ? count - 1 : options.scan;
  std::printf("# scan stamp index x y corner_angle_deg orientation_deg response turn\n");
  const ContourParams params = options.method_options.settings().contour;
  for (int k = first; k <= last; ++k) {
    const LaserScan &scan = log.entries[k].scan;
    const ContourFeatures features = extractContourFeatures(scan, params);
    int index = 0;
    for (const SpecialPoint &p : features.special_points)
      std::printf("%d %.6f %d %.4f %.4f %.2f %.2f %.4f %+d\n", k, scan.stamp, index++, p.position.x(), p.position.y(),
                  p.corner_angle * 180.0 / M_PI, p.orientation * 180.0 / M_PI, p.response, p.turn);
    if (!options.all)
      std::fprintf(stderr, "scan %d: %zu beams, %zu segments, %zu special points\n", k, scan.ranges.size(),
                   features.segments.size(), features.special_points.size());
  }
  return 0;
}

}  // namespace

void addFeaturesCommand(CLI::App &app) {
  auto options = std::make_shared<FeaturesOptions>();
  CLI::App *command = app.add_subcommand("features", "Print the special points (corners) of scans of a log");
  command->add_option("input", options->input, "CARMEN log, ROS 1 or ROS 2 bag or PCD folder")
      ->required()
      ->check(CLI::ExistingPath);
  command->add_option("--scan", options->scan, "Index of the scan, in stamp order")
      ->capture_default_str()
      ->check(nonNegative());
  command->add_flag("--all", options->all, "Every scan of the log");
  addReadOptions(*command, options->read);
  addMethodOptions(*command, options->method_options);
  command->callback([options]() {
    validateMethodOptions(options->method_options);
    runCommand([&] { return runFeatures(*options); });
  });
}

}  // namespace contour_reg::cli
