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
  ScanPair pair;
  std::string out;
  std::vector<std::string> methods;
  io::LogReadOptions read;
  MethodOptions method_options;
};

int runDebug(const DebugOptions &options) {
  pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
  io::ScanLog log;
  if (!readScanPair(options.pair, options.read, log)) return 2;
  const odometry::MatcherSettings settings = options.method_options.settings();
  DebugDumper dumper(options.out, settings);
  for (const std::string &file :
       dumper.dumpPair(log, std::size_t(options.pair.target()), std::size_t(options.pair.scan), options.methods))
    std::printf("%s\n", file.c_str());
  return 0;
}

}  // namespace

void addDebugCommand(CLI::App &app) {
  auto options = std::make_shared<DebugOptions>();
  CLI::App *command = app.add_subcommand("debug", "Debug images of a scan and of its registration to another scan");
  addScanPairOptions(*command, options->pair, "Scan to draw (the source of the pair; index in stamp order)");
  command->add_option("--out", options->out, "Output folder")->required();
  command->add_option("--methods", options->methods, "Also draw these methods' alignments side by side")
      ->check(methodCheck());
  addReadOptions(*command, options->read);
  addMethodOptions(*command, options->method_options);
  command->callback([options]() {
    checkScanPair(options->pair);
    validateMethodOptions(options->method_options);
    prepareOutputFolder("--out", options->out);
    runCommand([&] { return runDebug(*options); });
  });
}

}  // namespace contour_reg::cli
