#pragma once
// The world and paths the simulate and experiment commands drive through: the built-in
// office with its hand-placed paths, the built-in door row with its line, or a map file with
// the paths placed automatically or read from a paths file.

#include <map>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <Eigen/Core>

#include "contour_reg/simulation/simulated_run.h"
#include "contour_reg/simulation/world.h"

namespace contour_reg::cli {

struct ScenarioOptions {
  std::string map = "office";  ///< "office", "doors" or a map file (.yaml, .pgm, .png)
  double resolution = 0.1;     ///< m per pixel of a map image without YAML
  std::string paths_file;      ///< lines "NAME x0 y0 x1 y1 ..." in map metres
  std::string lidar = "hokuyo";
  std::string motion = "stop-and-go";
  double speed = 0.5;
  double odometry_noise = 0.02;
  double odometry_rate = 50.0;
  int people = 0;                        ///< people walking about each path (simulation/walkers.h)
  std::optional<io::Pose2D> laser_pose;  ///< the LIDAR on the robot; unset: at its centre
};

/// --map, --resolution, --paths-file, --lidar, --motion, --speed, --odometry-noise, --odometry-rate,
/// --people, --laser-pose.
void addScenarioOptions(CLI::App &command, ScenarioOptions &options);

struct Scenario {
  std::string map_name;  ///< "office", "doors" or the map file's stem
  simulation::World world;
  std::map<std::string, std::vector<Eigen::Vector2d>> paths;  ///< by name
};

/// Loads the world and the paths named `names` (S, L, Y, O, line; or names in the paths
/// file). Throws io::ReadError when the map or paths file is unreadable or a path does not fit.
Scenario loadScenario(const ScenarioOptions &options, const std::vector<std::string> &names);

/// The run settings the options describe, at LIDAR `rate` with `seed`.
simulation::RunSettings runSettings(const ScenarioOptions &options, double rate, unsigned seed);

}  // namespace contour_reg::cli
