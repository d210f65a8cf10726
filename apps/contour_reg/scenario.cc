#include "scenario.h"

#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>

#include "cli_options.h"
#include "contour_reg/io/scan_log.h"
#include "contour_reg/simulation/office.h"
#include "contour_reg/simulation/paths.h"

namespace contour_reg::cli {

namespace {

std::map<std::string, std::vector<Eigen::Vector2d>> readPathsFile(const std::string &path) {
  std::ifstream in(path);
  if (!in) throw io::ReadError(path + ": cannot open the paths file");
  std::map<std::string, std::vector<Eigen::Vector2d>> paths;
  std::string line;
  for (std::size_t number = 1; std::getline(in, line); ++number) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    std::string name;
    fields >> name;
    if (name.empty()) continue;
    std::vector<double> values;
    for (double v; fields >> v;) values.push_back(v);
    if (!fields.eof() || values.size() < 4 || values.size() % 2 != 0)
      throw io::ReadError(path + ":" + std::to_string(number) + ": expected NAME x0 y0 x1 y1 ... (two points or more)");
    std::vector<Eigen::Vector2d> waypoints;
    for (std::size_t k = 0; k < values.size(); k += 2) waypoints.emplace_back(values[k], values[k + 1]);
    paths[name] = waypoints;
  }
  return paths;
}

}  // namespace

void addScenarioOptions(CLI::App &command, ScenarioOptions &options) {
  command
      .add_option("--map", options.map,
                  "office or doors (built in: the door row, path line) or a map: map_server YAML, or a PGM/PNG with "
                  "--resolution")
      ->capture_default_str()
      ->check(CLI::Validator(
          [](std::string &map) -> std::string {
            return simulation::isBuiltInWorld(map) || std::filesystem::exists(map) ? "" : map + ": no such file";
          },
          "office, doors or FILE"));
  command.add_option("--resolution", options.resolution, "Metres per pixel of a map image given without YAML")
      ->capture_default_str()
      ->check(positive());
  command
      .add_option("--paths-file", options.paths_file,
                  "Paths in map metres, one per line: NAME x0 y0 x1 y1 ... (default: S, L, Y, O placed in the map)")
      ->check(CLI::ExistingFile);
  command
      .add_option("--lidar", options.lidar,
                  "hokuyo (UTM-30LX-like), ydlidar (X4-like) or sick (LMS200-like: 181 beams, 1 deg)")
      ->check(CLI::IsMember(simulation::lidarModelNames()))
      ->capture_default_str();
  command.add_option("--motion", options.motion, "stop-and-go (scans at rest) or continuous (distorted scans)")
      ->check(CLI::IsMember(simulation::motionNames()))
      ->capture_default_str();
  command.add_option("--speed", options.speed, "Robot speed (m/s)")->capture_default_str()->check(positive());
  command.add_option("--odometry-noise", options.odometry_noise, "Relative wheel odometry noise (>= 0)")
      ->capture_default_str()
      ->check(nonNegative());
  command
      .add_option("--odometry-rate", options.odometry_rate,
                  "Wheel odometry samples logged per second, between the scans too (Hz, 0: at the scans only)")
      ->capture_default_str()
      ->check(nonNegative());
  command
      .add_option("--people", options.people,
                  "People walking about each path: circles of 0.2-0.25 m at 0.5-1.5 m/s, placed with the seed")
      ->capture_default_str()
      ->check(nonNegative());
  addLaserPoseOption(command, options.laser_pose, "where the simulated LIDAR is mounted (default: 0 0 0)");
}

Scenario loadScenario(const ScenarioOptions &options, const std::vector<std::string> &names) {
  Scenario scenario;
  const bool built_in = simulation::isBuiltInWorld(options.map);
  if (built_in) {
    scenario.map_name = options.map;
    scenario.world = simulation::makeBuiltInWorld(options.map);
  } else {
    simulation::MapReadOptions read;
    read.resolution = options.resolution;
    scenario.map_name = std::filesystem::path(options.map).stem().string();
    scenario.world.setGrid(
        std::make_shared<simulation::OccupancyGrid>(simulation::readOccupancyGrid(options.map, read)));
  }
  const auto from_file = options.paths_file.empty() ? std::map<std::string, std::vector<Eigen::Vector2d>>()
                                                    : readPathsFile(options.paths_file);
  for (const std::string &name : names) {
    std::vector<Eigen::Vector2d> waypoints;
    if (!options.paths_file.empty()) {
      const auto found = from_file.find(name);
      if (found == from_file.end()) throw io::ReadError(options.paths_file + ": no path named '" + name + "'");
      waypoints = found->second;
    } else if (built_in) {
      waypoints = simulation::builtInPath(options.map, name);
      if (waypoints.empty())
        throw io::ReadError("unknown path '" + name + "' in " + simulation::builtInPathChoices(options.map));
    } else {
      const auto shape = simulation::pathShape(name);
      if (shape.empty()) throw io::ReadError("unknown path '" + name + "' (S, L, Y, O)");
      waypoints = simulation::placePath(scenario.world, shape);
      if (waypoints.empty())
        throw io::ReadError(options.map + ": path " + name + " fits nowhere in the map; give one with --paths-file");
    }
    scenario.paths[name] = waypoints;
  }
  return scenario;
}

simulation::RunSettings runSettings(const ScenarioOptions &options, double rate, unsigned seed) {
  simulation::RunSettings settings;
  settings.lidar = simulation::lidarModelNamed(options.lidar).value();  // checked by --lidar
  settings.rate = rate;
  settings.speed = options.speed;
  settings.motion = simulation::motionNamed(options.motion).value();  // checked by --motion
  settings.odometry_noise = options.odometry_noise;
  settings.odometry_rate = options.odometry_rate;
  settings.seed = seed;
  settings.people = options.people;
  settings.laser_pose = options.laser_pose.value_or(io::Pose2D{});
  return settings;
}

}  // namespace contour_reg::cli
