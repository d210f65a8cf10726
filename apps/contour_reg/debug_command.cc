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
  PairMotions motions;  // in `frame`
  std::string frame = "laser";
  bool log_poses = false;    // the reference from the log's own poses
  std::string ground_truth;  // the reference from this TUM trajectory
  io::LogReadOptions read;
  MethodOptions method_options;
};

// The robot's poses at the pair's target and source scans, from the log's own poses or the
// ground truth; false, with the error on stderr, when there are none.
bool referencePoses(const DebugOptions &options, const io::ScanLog &log, std::optional<io::Pose2D> &target,
                    std::optional<io::Pose2D> &source) {
  const io::LogEntry &a = log.entries[std::size_t(options.pair.target())],
                     &b = log.entries[std::size_t(options.pair.scan)];
  std::string from = options.ground_truth;
  if (options.log_poses) {
    target = a.odometry;
    source = b.odometry;
    from = options.pair.input + "'s poses";
  } else {
    std::string why;
    const auto poses = groundTruthAtScans(options.ground_truth, log, why);
    if (!poses) {
      std::fprintf(stderr, "error: %s\n", why.c_str());
      return false;
    }
    target = (*poses)[std::size_t(options.pair.target())];
    source = (*poses)[std::size_t(options.pair.scan)];
  }
  if (target && source) return true;
  std::fprintf(stderr, "error: %s: no pose at scan %d (stamp %.6f s) or scan %d (stamp %.6f s)\n", from.c_str(),
               options.pair.target(), a.scan.stamp, options.pair.scan, b.scan.stamp);
  return false;
}

int runDebug(const DebugOptions &options) {
  pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
  io::ScanLog log;
  if (!readScanPair(options.pair, options.read, log)) return 2;
  const odometry::MatcherSettings settings = options.method_options.settings();
  DebugDumper dumper(options.out, settings);
  // The pictures are the laser's; with the log's mounting, motions given in the robot's frame are turned into it.
  PairMotions motions = options.motions;
  if (options.frame == "robot" && log.laser_pose)
    for (std::optional<io::Pose2D> *motion : {&motions.guess, &motions.reference})
      if (*motion) *motion = io::laserMotion(**motion, *log.laser_pose);
  if (options.log_poses || !options.ground_truth.empty()) {
    std::optional<io::Pose2D> target, source;  // the robot's
    if (!referencePoses(options, log, target, source)) return 1;
    motions.reference = io::between(*target, *source);
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
  addMotionOption(*command, "--guess", options->motions.guess,
                  "Initial guess of the motion, in the frame of --frame (m, m, deg; default: none): every "
                  "registration drawn starts from it");
  CLI::Option *reference =
      addMotionOption(*command, "--reference", options->motions.reference,
                      "The pair's true motion, when known (a ground truth's), in the frame of --frame (m, m, deg): "
                      "methods_M_N.png shows the source moved by it first, and how far each method's motion lies from "
                      "it (without --methods, the contour method's)");
  CLI::Option *log_poses = command->add_flag(
      "--log-poses", options->log_poses,
      "The pair's true motion from the log's own poses (the corrected poses of the Radish logs; a raw log's "
      "wheel odometry), as --reference");
  CLI::Option *truth = command
                           ->add_option("--gt", options->ground_truth,
                                        "The pair's true motion from this TUM ground truth, interpolated at the "
                                        "scans' stamps, as --reference")
                           ->check(CLI::ExistingFile);
  reference->excludes(log_poses)->excludes(truth);
  log_poses->excludes(reference)->excludes(truth);
  truth->excludes(reference)->excludes(log_poses);
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
