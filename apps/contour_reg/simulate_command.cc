// contour_reg simulate: a CARMEN log and TUM ground truth of a path through a world.
#include <cstdio>
#include <filesystem>
#include <memory>

#include "cli_options.h"
#include "commands.h"
#include "contour_reg/io/read_log.h"
#include "contour_reg/io/trajectory.h"
#include "scenario.h"

namespace contour_reg::cli {

namespace {

struct SimulateOptions {
  std::string output, ground_truth, path = "L";
  double rate = 2.0;
  unsigned seed = 1;
  ScenarioOptions scenario;
};

int runSimulate(const SimulateOptions &options) {
  const Scenario scenario = loadScenario(options.scenario, {options.path});
  const auto &waypoints = scenario.paths.at(options.path);
  const simulation::RunSettings settings = runSettings(options.scenario, options.rate, options.seed);
  const simulation::SimulatedRun run = simulation::simulateRun(scenario.world, waypoints, settings);
  io::writeLog(options.output, run.log);
  io::writeTum(options.ground_truth, run.ground_truth);
  std::fprintf(stderr, "simulated %zu scans along path %s (%.1f m) in %s with %s, %s\n", run.log.entries.size(),
               options.path.c_str(), run.path_length, scenario.map_name.c_str(), settings.lidar.name.c_str(),
               options.scenario.motion.c_str());
  std::fprintf(stderr, "written: %s, ground truth %s\n", options.output.c_str(), options.ground_truth.c_str());
  return 0;
}

}  // namespace

void addSimulateCommand(CLI::App &app) {
  auto options = std::make_shared<SimulateOptions>();
  CLI::App *command = app.add_subcommand("simulate", "Simulate a LIDAR log along a path through a map");
  command
      ->add_option("--output,-o,--out", options->output,
                   "Log to write: a ROS 1 bag (.bag: /scan with the beam timing of --motion continuous, "
                   "/odom), a ROS 2 bag's storage file (.db3: sqlite3, .mcap: MCAP; the same topics) or a CARMEN log "
                   "(any other name)")
      ->required();
  command->add_option("--gt", options->ground_truth,
                      "TUM ground truth to write (default: OUTPUT_STEM.gt.tum beside the log, where compare finds it)");
  command->add_option("--path", options->path, "S, L, Y, O, line (office) or a name in --paths-file")
      ->capture_default_str();
  command->add_option("--rate", options->rate, "LIDAR rate (Hz): sets the spacing between scans")
      ->capture_default_str()
      ->check(positive());
  command->add_option("--seed", options->seed, "Random seed")->capture_default_str();
  addScenarioOptions(*command, options->scenario);
  command->callback([options]() {
    checkOutputFile("--output", options->output);
    if (options->ground_truth.empty()) {
      const std::filesystem::path output(options->output);
      options->ground_truth = (output.parent_path() / (logStem(options->output) + ".gt.tum")).string();
    }
    checkOutputFile("--gt", options->ground_truth);
    runCommand([&] { return runSimulate(*options); });
  });
}

}  // namespace contour_reg::cli
