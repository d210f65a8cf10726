// contour_reg convert: a log written again in another format, its kind by the output's name.
#include <cstdio>
#include <memory>

#include "cli_options.h"
#include "commands.h"
#include "contour_reg/io/read_log.h"

namespace contour_reg::cli {

namespace {

struct ConvertOptions {
  std::string input, output;
  io::LogReadOptions read;
};

int runConvert(const ConvertOptions &options) {
  const io::ScanLog log = io::readLog(options.input, options.read);
  printReadReport(log);
  io::writeLog(options.output, log);
  std::fprintf(stderr, "written: %s, %zu scans, %zu odometry samples%s\n", options.output.c_str(), log.entries.size(),
               log.wheel_odometry.size(), log.laser_pose ? ", the laser's mounting" : "");
  return 0;
}

}  // namespace

void addConvertCommand(CLI::App &app) {
  auto options = std::make_shared<ConvertOptions>();
  CLI::App *command = app.add_subcommand(
      "convert",
      "Write a log in another format: a ROS 1 bag (.bag), a ROS 2 bag's storage file (.db3, .mcap) or a "
      "CARMEN log (any other name)");
  command->add_option("input", options->input, "CARMEN log, ROS 1 or ROS 2 bag or PCD folder")
      ->required()
      ->check(CLI::ExistingPath);
  command->add_option("output", options->output, "Log to write, its format by its name")->required();
  addReadOptions(*command, options->read);
  command->callback([options]() {
    checkOutputFile("output", options->output);
    runCommand([&] { return runConvert(*options); });
  });
}

}  // namespace contour_reg::cli
