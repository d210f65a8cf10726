// contour_reg debug: pictures of what the contour method saw in a scan and a pair.
#include <cstdio>
#include <filesystem>
#include <memory>

#include <pcl/console/print.h>

#include "cli_options.h"
#include "commands.h"
#include "contour_reg/drawing/debug_images.h"
#include "contour_reg/io/pose2d.h"
#include "contour_reg/io/read_log.h"
#include "debug_dump.h"

namespace contour_reg::cli {

namespace {

struct DebugOptions {
  ScanPair pair;
  std::string out;
  std::vector<std::string> methods;
  std::optional<io::Pose2D> guess;  // in `frame`
  ReferenceOptions reference;
  std::string frame = "laser";
  io::LogReadOptions read;
  MethodOptions method_options;
};

int runDebug(const DebugOptions &options) {
  pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
  io::ScanLog log;
  if (!readScanPair(options.pair, options.read, log)) return 2;
  const odometry::MatcherSettings settings = options.method_options.settings();
  DebugDumper dumper(options.out, settings);
  // The pictures are the laser's; with the log's mounting, motions given in the robot's frame are turned into it.
  PairMotions motions{options.guess, options.reference.motion};
  if (options.frame == "robot" && log.laser_pose)
    for (std::optional<io::Pose2D> *motion : {&motions.guess, &motions.reference})
      if (*motion) *motion = io::laserMotion(**motion, *log.laser_pose);
  if (options.reference.fromPoses()) {
    motions.reference = referenceFromPoses(options.reference, options.pair, log);  // the robot's
    if (!motions.reference) return 1;
    if (log.laser_pose) motions.reference = io::laserMotion(*motions.reference, *log.laser_pose);
  }
  for (const std::string &file : dumper.dumpPair(log, std::size_t(options.pair.target()),
                                                 std::size_t(options.pair.scan), options.methods, motions))
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
  addMotionOption(*command, "--guess", options->guess,
                  "Initial guess of the motion, in the frame of --frame (m, m, deg; default: none): every "
                  "registration drawn starts from it");
  addReferenceOptions(*command, options->reference,
                      "The pair's true motion, when known (a ground truth's), in the frame of --frame (m, m, deg): "
                      "methods_M_N.png shows the source moved by it first, and how far each method's motion lies from "
                      "it (without --methods, the contour method's)");
  addFrameOption(*command, options->frame, "--guess and --reference (the pictures are the laser's)");
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
