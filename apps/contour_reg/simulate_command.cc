// contour_reg simulate: a CARMEN log and TUM ground truth of a path through a world.
#include <cmath>
#include <cstdio>
#include <memory>
#include <random>

#include "commands.h"
#include "contour_reg/io/carmen.h"
#include "contour_reg/io/trajectory.h"
#include "contour_reg/simulation/lidar.h"
#include "contour_reg/simulation/office.h"
#include "contour_reg/simulation/paths.h"

namespace contour_reg::cli {

namespace {

struct SimulateOptions {
  std::string output, ground_truth, path = "L", lidar = "hokuyo";
  double rate = 2.0, speed = 0.5, odometry_noise = 0.02;
  unsigned seed = 1;
};

io::Pose2D toPose(const Eigen::Isometry2d &pose) {
  return {pose.translation().x(), pose.translation().y(), std::atan2(pose.linear()(1, 0), pose.linear()(0, 0))};
}

int runSimulate(const SimulateOptions &options) {
  const auto waypoints = simulation::officePath(options.path);
  if (waypoints.empty()) {
    std::fprintf(stderr, "error: unknown path '%s' (S, L, Y, O, line)\n", options.path.c_str());
    return 2;
  }
  const simulation::LidarModel model =
      options.lidar == "ydlidar" ? simulation::LidarModel::ydlidarX4() : simulation::LidarModel::hokuyoUtm30lx();
  const simulation::World world = simulation::makeOfficeWorld();
  // Stop and go: one scan at rest every speed / rate metres.
  const auto poses = simulation::samplePath(waypoints, options.speed / options.rate);
  std::mt19937 rng(options.seed);
  std::normal_distribution<double> unit(0.0, 1.0);

  io::ScanLog log;
  io::Trajectory truth;
  Eigen::Isometry2d odometry = poses.front();
  for (std::size_t k = 0; k < poses.size(); ++k) {
    if (k > 0) {  // wheel odometry: the true increment with proportional noise
      const Eigen::Isometry2d step = poses[k - 1].inverse() * poses[k];
      const double yaw = std::atan2(step.linear()(1, 0), step.linear()(0, 0));
      const double scale = 1.0 + options.odometry_noise * unit(rng);
      Eigen::Isometry2d noisy = Eigen::Isometry2d::Identity();
      noisy.translate(step.translation() * scale);
      noisy.rotate(yaw * (1.0 + options.odometry_noise * unit(rng)) + 0.2 * options.odometry_noise * unit(rng) * step.translation().norm());
      odometry = odometry * noisy;
    }
    io::LogEntry entry;
    entry.scan = simulation::simulateScan(world, poses[k], model, rng);
    entry.scan.stamp = static_cast<double>(k) / options.rate;
    entry.odometry = toPose(odometry);
    truth.push_back({entry.scan.stamp, toPose(poses[k])});
    log.entries.push_back(std::move(entry));
  }
  io::writeCarmen(options.output, log);
  if (!options.ground_truth.empty()) io::writeTum(options.ground_truth, truth);
  std::fprintf(stderr, "simulated %zu scans along path %s (%.1f m) with %s\n", poses.size(), options.path.c_str(),
               simulation::pathLength(waypoints), model.name.c_str());
  return 0;
}

}  // namespace

void addSimulateCommand(CLI::App &app) {
  auto options = std::make_shared<SimulateOptions>();
  CLI::App *command = app.add_subcommand("simulate", "Simulate a LIDAR log along a path through the built-in office");
  command->add_option("--out", options->output, "CARMEN log to write")->required();
  command->add_option("--gt", options->ground_truth, "TUM ground truth to write");
  command->add_option("--path", options->path, "S, L, Y, O or line")->capture_default_str();
  command->add_option("--lidar", options->lidar, "hokuyo (UTM-30LX-like) or ydlidar (X4-like)")->capture_default_str();
  command->add_option("--rate", options->rate, "LIDAR rate (Hz): sets the spacing between scans")->capture_default_str()->check(CLI::PositiveNumber);
  command->add_option("--speed", options->speed, "Robot speed (m/s)")->capture_default_str()->check(CLI::PositiveNumber);
  command->add_option("--odometry-noise", options->odometry_noise, "Relative wheel odometry noise")->capture_default_str();
  command->add_option("--seed", options->seed, "Random seed")->capture_default_str();
  command->callback([options]() { runCommand([&] { return runSimulate(*options); }); });
}

}  // namespace contour_reg::cli
