#include "contour_reg/simulation/simulated_run.h"

#include <cmath>
#include <random>

#include "contour_reg/io/pose2d.h"
#include "contour_reg/simulation/paths.h"

namespace contour_reg::simulation {

namespace {

io::Pose2D toPose(const Eigen::Isometry2d &pose) { return io::toPose(pose.matrix()); }

}  // namespace

SimulatedRun simulateRun(const World &world, const std::vector<Eigen::Vector2d> &waypoints,
                         const RunSettings &settings) {
  SimulatedRun run;
  run.path_length = pathLength(waypoints);
  run.log.source = "simulation";
  run.log.laser_pose = settings.laser_pose;
  if (waypoints.size() < 2 || !(settings.rate > 0.0) || !(settings.speed > 0.0)) return run;
  std::mt19937 rng(settings.seed);
  std::normal_distribution<double> unit(0.0, 1.0);

  const double period = 1.0 / settings.rate;
  const double spacing = settings.speed * period;
  const auto scans = static_cast<std::size_t>(std::ceil(run.path_length / spacing - 1e-9)) + 1;
  const LidarModel &lidar = settings.lidar;
  // The LIDAR's pose when the robot is at `robot`.
  const Eigen::Isometry2d mounting(io::toMatrix(settings.laser_pose));
  auto sensorAt = [&](const Eigen::Isometry2d &robot) -> Eigen::Isometry2d { return robot * mounting; };
  Eigen::Isometry2d previous_truth = poseAlongPath(waypoints, 0.0, settings.turn_radius);
  Eigen::Isometry2d odometry = previous_truth;
  for (std::size_t k = 0; k < scans; ++k) {
    const double stamp = static_cast<double>(k) * period;
    const double s = std::min(static_cast<double>(k) * spacing, run.path_length);
    const Eigen::Isometry2d truth = poseAlongPath(waypoints, s, settings.turn_radius);
    io::LogEntry entry;
    if (settings.motion == Motion::kStopAndGo || k + 1 == scans) {
      entry.scan = simulateScan(world, sensorAt(truth), lidar, rng);
    } else {
      // The LIDAR turns once per period; beam n fires at its bearing's share of a turn.
      const double beam_time = beamInterval(period, lidar.angleIncrement());
      entry.scan = simulateScan(
          world,
          [&](std::size_t n) {
            return sensorAt(poseAlongPath(waypoints, s + settings.speed * beam_time * static_cast<double>(n),
                                          settings.turn_radius));
          },
          lidar, rng);
      entry.scan.time_increment = beam_time;
    }
    entry.scan.stamp = stamp;
    if (k > 0) {  // wheel odometry: the true increment with proportional noise
      const Eigen::Isometry2d step = previous_truth.inverse() * truth;
      const double scale = 1.0 + settings.odometry_noise * unit(rng);
      const double yaw = toPose(step).yaw * (1.0 + settings.odometry_noise * unit(rng)) +
                         0.2 * settings.odometry_noise * unit(rng) * step.translation().norm();
      Eigen::Isometry2d noisy = Eigen::Isometry2d::Identity();
      noisy.translate(step.translation() * scale);
      noisy.rotate(yaw);
      odometry = odometry * noisy;
    }
    entry.odometry = toPose(odometry);
    run.ground_truth.push_back({stamp, toPose(truth)});
    run.log.entries.push_back(std::move(entry));
    previous_truth = truth;
  }
  return run;
}

}  // namespace contour_reg::simulation
