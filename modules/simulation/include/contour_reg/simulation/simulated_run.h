#pragma once
/// @file simulated_run.h
/// A robot driving a path through a world with a LIDAR: the scans it logs, its wheel
/// odometry and its true poses, ready for the same readers and metrics as a real log.

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "contour_reg/io/scan_log.h"
#include "contour_reg/io/trajectory.h"
#include "contour_reg/simulation/lidar.h"
#include "contour_reg/simulation/world.h"

namespace contour_reg::simulation {

enum class Motion {
  kStopAndGo,   ///< the robot stands still while the LIDAR sweeps (the paper's experiment)
  kContinuous,  ///< the robot keeps moving; each beam is taken from where the robot is when it fires
};

/// The motions the command line and Python name: stop-and-go, continuous (the enum's order);
/// the motion of a name, none for another name.
const std::vector<std::string> &motionNames();
std::optional<Motion> motionNamed(const std::string &name);

struct RunSettings {
  LidarModel lidar = LidarModel::hokuyoUtm30lx();
  double rate = 2.0;   ///< Hz, LIDAR revolutions per second: one scan per revolution
  double speed = 0.5;  ///< m/s along the path; the scans lie speed / rate m apart
  Motion motion = Motion::kStopAndGo;
  double turn_radius = 0.4;      ///< m, see poseAlongPath
  double odometry_noise = 0.02;  ///< relative standard deviation of the wheel odometry increments
  double odometry_rate = 50.0;   ///< Hz, wheel odometry samples logged (ScanLog::wheel_odometry); 0: none
  unsigned seed = 1;             ///< fixes range noise, dropout and odometry noise
  io::Pose2D laser_pose;         ///< the LIDAR's pose on the robot (base_link -> laser)
  int people = 0;                ///< people walking about the path (walkers.h), placed with `seed`
};

struct SimulatedRun {
  io::ScanLog log;              ///< scans stamped k / rate s, wheel odometry at each and between, the mounting
  io::Trajectory ground_truth;  ///< the robot's true pose at each scan stamp
  double path_length = 0.0;     ///< m
};

/// Throws std::invalid_argument, with the run's size, when driving a path of `length` m with
/// `settings` would log more than a million scans or ten million wheel odometry samples.
void checkRunSize(double length, const RunSettings &settings);

/// Drives `waypoints` through `world`. Scan k is stamped k / rate; in continuous motion its
/// beams fire over the revolution that starts then, so the later beams see the world from
/// further along the path. The robot drives the path at constant speed between the scans'
/// poses; its wheel odometry is logged at odometry_rate and at every scan stamp, each
/// increment between scans carrying its noise in proportion to how far along it the robot is.
/// Throws std::invalid_argument when the run is too long to log (checkRunSize): a path too
/// long or not finite, a speed too low, a rate too high.
SimulatedRun simulateRun(const World &world, const std::vector<Eigen::Vector2d> &waypoints,
                         const RunSettings &settings);

}  // namespace contour_reg::simulation
