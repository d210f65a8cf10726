#include "contour_reg/simulation/simulated_run.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <stdexcept>

#include "contour_reg/io/pose2d.h"
#include "contour_reg/simulation/paths.h"
#include "contour_reg/simulation/walkers.h"

namespace contour_reg::simulation {

namespace {

io::Pose2D toPose(const Eigen::Isometry2d &pose) { return io::toPose(pose.matrix()); }

// The most scans and wheel odometry samples a run holds: a million scans are days of a LIDAR
// at 2 Hz and gigabytes of log. A longer run is an error in its settings.
constexpr double kMostScans = 1e6;
constexpr double kMostOdometrySamples = 1e7;

}  // namespace

void checkRunSize(double length, const RunSettings &settings) {
  const double duration = length / settings.speed;
  const double scans = std::ceil(duration * settings.rate) + 1.0;
  const double samples = duration * settings.odometry_rate;
  char message[200];
  if (!(scans <= kMostScans)) {
    std::snprintf(message, sizeof message,
                  "a run of %.3g scans (a path of %.3g m at %.3g m/s, %.3g scans a second): more than %.0f", scans,
                  length, settings.speed, settings.rate, kMostScans);
    throw std::invalid_argument(message);
  }
  if (!(samples <= kMostOdometrySamples)) {
    std::snprintf(message, sizeof message,
                  "a run of %.3g wheel odometry samples (%.3g s at %.3g a second): more than %.0f", samples, duration,
                  settings.odometry_rate, kMostOdometrySamples);
    throw std::invalid_argument(message);
  }
}

const std::vector<std::string> &motionNames() {
  static const std::vector<std::string> names{"stop-and-go", "continuous"};
  return names;
}

std::optional<Motion> motionNamed(const std::string &name) {
  const auto &names = motionNames();
  const auto at = std::find(names.begin(), names.end(), name);
  if (at == names.end()) return std::nullopt;
  return static_cast<Motion>(at - names.begin());
}

SimulatedRun simulateRun(const World &world, const std::vector<Eigen::Vector2d> &waypoints,
                         const RunSettings &settings) {
  SimulatedRun run;
  run.path_length = pathLength(waypoints);
  run.log.source = "simulation";
  run.log.laser_pose = settings.laser_pose;
  if (waypoints.size() < 2 || !(settings.rate > 0.0) || !(settings.speed > 0.0)) return run;
  checkRunSize(run.path_length, settings);
  std::mt19937 rng(settings.seed);
  std::normal_distribution<double> unit(0.0, 1.0);

  const double period = 1.0 / settings.rate;
  const double spacing = settings.speed * period;
  const auto scans = static_cast<std::size_t>(std::ceil(run.path_length / spacing - 1e-9)) + 1;
  const LidarModel &lidar = settings.lidar;
  // The LIDAR's pose when the robot is at `robot`.
  const Eigen::Isometry2d mounting(io::toMatrix(settings.laser_pose));
  auto sensorAt = [&](const Eigen::Isometry2d &robot) -> Eigen::Isometry2d { return robot * mounting; };
  // The people walk on a generator of their own: a run without them keeps its noise.
  Walkers walkers(world, waypoints, settings.people, settings.seed + 7919u);
  Eigen::Isometry2d previous_truth = poseAlongPath(waypoints, 0.0, settings.turn_radius);
  Eigen::Isometry2d odometry = previous_truth;
  for (std::size_t k = 0; k < scans; ++k) {
    const double stamp = static_cast<double>(k) * period;
    const double s = std::min(static_cast<double>(k) * spacing, run.path_length);
    const Eigen::Isometry2d truth = poseAlongPath(waypoints, s, settings.turn_radius);
    io::LogEntry entry;
    walkers.advanceTo(stamp);
    const World seen = walkers.people().empty() ? World() : walkers.around(sensorAt(truth).translation());
    const World &scene = walkers.people().empty() ? world : seen;
    if (settings.motion == Motion::kStopAndGo || k + 1 == scans) {
      entry.scan = simulateScan(scene, sensorAt(truth), lidar, rng);
    } else {
      // The LIDAR turns once per period; beam n fires at its bearing's share of a turn.
      const double beam_time = beamInterval(period, lidar.angleIncrement());
      entry.scan = simulateScan(
          scene,
          [&](std::size_t n) {
            return sensorAt(poseAlongPath(waypoints, s + settings.speed * beam_time * static_cast<double>(n),
                                          settings.turn_radius));
          },
          lidar, rng);
      entry.scan.time_increment = beam_time;
    }
    entry.scan.stamp = stamp;
    if (k > 0) {  // wheel odometry: the true increment with proportional noise
      const double scale = 1.0 + settings.odometry_noise * unit(rng);
      const double yaw_scale = 1.0 + settings.odometry_noise * unit(rng);
      const double yaw_per_metre = 0.2 * settings.odometry_noise * unit(rng);
      // The odometry's increment from the last scan to the robot's true pose `to`.
      auto noisyIncrement = [&](const Eigen::Isometry2d &to) {
        const Eigen::Isometry2d step = previous_truth.inverse() * to;
        Eigen::Isometry2d noisy = Eigen::Isometry2d::Identity();
        noisy.translate(step.translation() * scale);
        noisy.rotate(toPose(step).yaw * yaw_scale + yaw_per_metre * step.translation().norm());
        return noisy;
      };
      if (settings.odometry_rate > 0.0) {  // the samples between the scans
        const double previous_stamp = stamp - period;
        for (double j = std::floor(previous_stamp * settings.odometry_rate) + 1.0;; j += 1.0) {
          const double t = j / settings.odometry_rate;
          if (t >= stamp - 1e-9) break;
          if (t <= previous_stamp + 1e-9) continue;
          const Eigen::Isometry2d at =
              poseAlongPath(waypoints, std::min(settings.speed * t, run.path_length), settings.turn_radius);
          run.log.wheel_odometry.push_back({t, toPose(odometry * noisyIncrement(at))});
        }
      }
      odometry = odometry * noisyIncrement(truth);
    }
    entry.odometry = toPose(odometry);
    if (settings.odometry_rate > 0.0) run.log.wheel_odometry.push_back({stamp, *entry.odometry});
    run.ground_truth.push_back({stamp, toPose(truth)});
    run.log.entries.push_back(std::move(entry));
    previous_truth = truth;
  }
  return run;
}

}  // namespace contour_reg::simulation
