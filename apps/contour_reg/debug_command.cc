// contour_reg debug: pictures of what the contour method saw in a scan and a pair.
#include <cstdio>
#include <filesystem>
#include <memory>

#include <pcl/console/print.h>

#include "cli_options.h"
#include "commands.h"
#include "contour_reg/drawing/debug_images.h"
#include "contour_reg/io/read_log.h"
#include "debug_dump.h"

namespace contour_reg::cli {

namespace {

struct DebugOptions {
  std::string input, out;
  int scan = 1, to = -1;
  std::vector<std::string> methods;
  io::LogReadOptions read;
  MethodOptions method_options;
};

int runDebug(const DebugOptions &options) {
  pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
  const io::ScanLog log = io::readLog(options.input, options.read);
  printReadReport(log);
  const int count = static_cast<int>(log.entries.size());
  const int target = options.to >= 0 ? options.to : options.scan - 1;
  if (options.scan >= count || target >= count) {
    std::fprintf(stderr, "error: --scan %d, --to %d: %s has scans 0..%d\n", options.scan, target, options.input.c_str(),
                 count - 1);
    return 2;
  }
  const odometry::MatcherSettings settings = options.method_options.settings();
  DebugDumper dumper(options.out, settings);
  for (const std::string &file : dumper.dumpPair(log, std::size_t(target), std::size_t(options.scan), options.methods))
    std::printf("%s\n", file.c_str());
  return 0;
}

}  // namespace

void addDebugCommand(CLI::App &app) {
  auto options = std::make_shared<DebugOptions>();
  CLI::App *command = app.add_subcommand("debug", "Debug images of a scan and of its registration to another scan");
  command->add_option("input", options->input, "CARMEN log, ROS bag or PCD folder")
      ->required()
      ->check(CLI::ExistingPath);
  command->add_option("--scan", options->scan, "Scan to draw (the source of the pair; index in stamp order)")
      ->capture_default_str()
      ->check(nonNegative());
  command->add_option("--to", options->to, "Target scan of the pair (default: the scan before)")->check(nonNegative());
  command->add_option("--out", options->out, "Output folder")->required();
  command->add_option("--methods", options->methods, "Also draw these methods' alignments side by side")
      ->check(methodCheck());
  addReadOptions(*command, options->read);
  addMethodOptions(*command, options->method_options);
  command->callback([options]() {
    if (options->scan == 0 && options->to < 0)
      throw CLI::ValidationError("--scan", "scan 0 has no scan before it: give --to");
    validateMethodOptions(options->method_options);
    prepareOutputFolder("--out", options->out);
    runCommand([&] { return runDebug(*options); });
  });
}

}  // namespace contour_reg::cli
