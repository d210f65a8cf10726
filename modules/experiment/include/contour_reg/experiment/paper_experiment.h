#pragma once
/// @file paper_experiment.h
/// The paper's experiment (ALGORITHM.md, section G; the paper's Table 1): a robot drives
/// each path shape several times ("arrivals") at each LIDAR rate, every method runs
/// odometry on the very same scans, and the error of the end position over the path length
/// is taken per arrival; a cell of the table is the median over the arrivals.

#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "contour_reg/io/trajectory.h"
#include "contour_reg/odometry/odometry.h"
#include "contour_reg/odometry/scan_matcher.h"
#include "contour_reg/simulation/simulated_run.h"
#include "contour_reg/simulation/world.h"

namespace contour_reg::experiment {

/// The name under which the log's own wheel odometry is reported beside the methods.
inline constexpr const char *kWheelOdometry = "wheel-odometry";

/// The paper's Table 1 median (percent of path length) for a path shape and LIDAR rate;
/// nothing for other shapes or rates.
std::optional<double> paperMedianPercent(const std::string &path, double rate);

struct ExperimentSettings {
  std::vector<std::string> methods = {"contour", "icp", "ndt2d"};
  std::vector<double> rates = {5.0, 2.0, 1.0};  ///< Hz
  int arrivals = 10;
  unsigned seed = 1;            ///< arrival a of every cell uses seed + a
  simulation::RunSettings run;  ///< the LIDAR, speed and motion; rate and seed are set per arrival
  /// Standard deviation of the shift of each waypoint per arrival, m: no two arrivals drive
  /// exactly the same line.
  double waypoint_jitter = 0.05;
  odometry::MatcherSettings matcher;
  odometry::GuessSource guess = odometry::GuessSource::kZero;
  bool deskew = true;                ///< OdometryOptions::deskew
  bool wheel_fusion = true;          ///< OdometryOptions::fuse_wheel_odometry
  odometry::WheelNoise wheel_noise;  ///< OdometryOptions::wheel_noise
  unsigned jobs = 0;                 ///< parallel arrivals (0: one per core)
  /// Called after every arrival with (arrivals done, arrivals in all).
  std::function<void(std::size_t, std::size_t)> progress;
};

/// One method on one arrival.
struct ArrivalResult {
  std::string path, method;
  double rate = 0.0;
  int arrival = 0;
  double path_length = 0.0;        ///< m
  double end_point_error = 0.0;    ///< m
  double end_point_percent = 0.0;  ///< of the path length
  std::size_t scans = 0, registrations = 0, failures = 0;
  double median_ms = 0.0;                 ///< per registration
  io::Trajectory estimate, ground_truth;  ///< kept for the first arrival only
};

/// One simulated drive of the experiment: a path at a LIDAR rate, the arrival-th time.
struct Arrival {
  std::string path;
  double rate = 0.0;
  int arrival = 0;
};

/// Every arrival of the experiment, in the order runExperiment gives their results: by path
/// (name order), rate (settings order), arrival. Each is an independent job.
std::vector<Arrival> planArrivals(const std::map<std::string, std::vector<Eigen::Vector2d>> &paths,
                                  const ExperimentSettings &settings);

/// Runs one arrival: simulates its drive, then each method (settings order) and the wheel
/// odometry on its scans. The same results whatever else runs and in whichever order.
std::vector<ArrivalResult> runArrival(const simulation::World &world,
                                      const std::map<std::string, std::vector<Eigen::Vector2d>> &paths,
                                      const ExperimentSettings &settings, const Arrival &arrival);

/// Runs every arrival (planArrivals), settings.jobs at a time. Results come in (path, rate,
/// arrival, method) order. An arrival that throws (simulateRun refuses a run too long to
/// simulate) stops the others; its exception is thrown here.
std::vector<ArrivalResult> runExperiment(const simulation::World &world,
                                         const std::map<std::string, std::vector<Eigen::Vector2d>> &paths,
                                         const ExperimentSettings &settings);

/// One cell of the table: a method on a path at a rate, over all arrivals.
struct CellSummary {
  std::string path, method;
  double rate = 0.0;
  double median_percent = 0.0, worst_percent = 0.0;
  std::size_t arrivals = 0, registrations = 0, failures = 0;
  double median_ms = 0.0;
};

/// Median (and worst) end-point error over the arrivals of each (path, rate, method).
std::vector<CellSummary> summarize(const std::vector<ArrivalResult> &results);

}  // namespace contour_reg::experiment
