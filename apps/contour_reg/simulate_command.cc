// contour_reg simulate: a CARMEN log and TUM ground truth of a path through a world.
#include <cstdio>
#include <memory>

#include "commands.h"
#include "contour_reg/io/carmen.h"
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
  io::writeCarmen(options.output, run.log);
  if (!options.ground_truth.empty()) io::writeTum(options.ground_truth, run.ground_truth);
  std::fprintf(stderr, "simulated %zu scans along path %s (%.1f m) in %s with %s, %s\n", run.log.entries.size(),
               options.path.c_str(), run.path_length, scenario.map_name.c_str(), settings.lidar.name.c_str(),
               options.scenario.motion.c_str());
  return 0;
}

}  // namespace

void addSimulateCommand(CLI::App &app) {
  auto options = std::make_shared<SimulateOptions>();
  CLI::App *command = app.add_subcommand("simulate", "Simulate a LIDAR log along a path through a map");
  command->add_option("--out", options->output, "CARMEN log to write")->required();
  command->add_option("--gt", options->ground_truth, "TUM ground truth to write");
  command->add_option("--path", options->path, "S, L, Y, O, line (office) or a name in --paths-file")
      ->capture_default_str();
  command->add_option("--rate", options->rate, "LIDAR rate (Hz): sets the spacing between scans")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  command->add_option("--seed", options->seed, "Random seed")->capture_default_str();
  addScenarioOptions(*command, options->scenario);
  command->callback([options]() { runCommand([&] { return runSimulate(*options); }); });
}

}  // namespace contour_reg::cli
