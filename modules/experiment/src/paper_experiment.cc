#include "contour_reg/experiment/paper_experiment.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <mutex>
#include <random>
#include <thread>

#include "contour_reg/evaluation/metrics.h"

namespace contour_reg::experiment {

std::optional<double> paperMedianPercent(const std::string &path, double rate) {
  // Table 1 of the paper: median over ten arrivals, per LIDAR rotation rate.
  static const std::map<double, std::map<std::string, double>> table = {
      {5.0, {{"S", 6.8}, {"L", 14.1}, {"Y", 4.4}, {"O", 5.4}}},
      {2.0, {{"S", 2.5}, {"L", 13.1}, {"Y", 2.1}, {"O", 2.6}}},
      {1.0, {{"S", 4.0}, {"L", 7.8}, {"Y", 2.8}, {"O", 2.4}}},
  };
  const auto row = table.find(rate);
  if (row == table.end()) return std::nullopt;
  const auto cell = row->second.find(path);
  if (cell == row->second.end()) return std::nullopt;
  return cell->second;
}

std::vector<Arrival> planArrivals(const std::map<std::string, std::vector<Eigen::Vector2d>> &paths,
                                  const ExperimentSettings &settings) {
  std::vector<Arrival> arrivals;
  for (const auto &[name, waypoints] : paths)
    for (double rate : settings.rates)
      for (int a = 0; a < settings.arrivals; ++a) arrivals.push_back({name, rate, a});
  return arrivals;
}

std::vector<ArrivalResult> runArrival(const simulation::World &world,
                                      const std::map<std::string, std::vector<Eigen::Vector2d>> &paths,
                                      const ExperimentSettings &settings, const Arrival &arrival) {
  const unsigned seed = settings.seed + static_cast<unsigned>(arrival.arrival);
  // The arrival's own line: every waypoint shifted a little, as no robot drives one line twice.
  std::vector<Eigen::Vector2d> waypoints = paths.at(arrival.path);
  std::mt19937 jitter(seed * 7919u + 17u);
  std::normal_distribution<double> shift(0.0, settings.waypoint_jitter > 0.0 ? settings.waypoint_jitter : 1.0);
  if (settings.waypoint_jitter > 0.0)
    for (Eigen::Vector2d &w : waypoints) w += Eigen::Vector2d(shift(jitter), shift(jitter));
  simulation::RunSettings run_settings = settings.run;
  run_settings.rate = arrival.rate;
  run_settings.seed = seed;
  const simulation::SimulatedRun run = simulation::simulateRun(world, waypoints, run_settings);

  odometry::OdometryOptions options;
  options.guess = settings.guess;
  options.deskew = settings.deskew;
  options.fuse_wheel_odometry = settings.wheel_fusion;
  options.wheel_noise = settings.wheel_noise;
  std::vector<ArrivalResult> results(settings.methods.size() + 1);
  for (std::size_t m = 0; m < results.size(); ++m) {
    ArrivalResult &result = results[m];
    result.path = arrival.path;
    result.rate = arrival.rate;
    result.arrival = arrival.arrival;
    result.path_length = run.path_length;
    result.scans = run.log.entries.size();
    io::Trajectory estimate;
    if (m < settings.methods.size()) {
      result.method = settings.methods[m];
      const auto matcher = odometry::makeScanMatcher(result.method, settings.matcher);
      const odometry::OdometryRun chained = odometry::runOdometry(run.log, *matcher, options);
      estimate = chained.trajectory;
      result.registrations = chained.stats.registrations;
      result.failures = chained.stats.failures;
      result.median_ms = evaluation::median(chained.stats.milliseconds);
    } else {
      result.method = kWheelOdometry;
      estimate = odometry::wheelOdometry(run.log);
    }
    const evaluation::EndPointError error =
        evaluation::endPointError(evaluation::associate(estimate, run.ground_truth));
    result.end_point_error = error.error;
    result.end_point_percent = error.percent;
    if (arrival.arrival == 0) {
      result.estimate = std::move(estimate);
      result.ground_truth = run.ground_truth;
    }
  }
  return results;
}

std::vector<ArrivalResult> runExperiment(const simulation::World &world,
                                         const std::map<std::string, std::vector<Eigen::Vector2d>> &paths,
                                         const ExperimentSettings &settings) {
  const std::vector<Arrival> arrivals = planArrivals(paths, settings);
  std::vector<std::vector<ArrivalResult>> by_arrival(arrivals.size());
  std::atomic<std::size_t> next{0}, done{0};
  std::exception_ptr failure;  // the first arrival's exception: the others stop, and it is thrown here
  std::mutex failure_mutex;
  auto worker = [&]() {
    for (std::size_t j = next++; j < arrivals.size(); j = next++) {
      try {
        by_arrival[j] = runArrival(world, paths, settings, arrivals[j]);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(failure_mutex);
        if (!failure) failure = std::current_exception();
        next = arrivals.size();
        return;
      }
      const std::size_t finished = ++done;
      if (settings.progress) settings.progress(finished, arrivals.size());
    }
  };
  const unsigned threads =
      std::max(1u, std::min<unsigned>(settings.jobs ? settings.jobs : std::thread::hardware_concurrency(),
                                      static_cast<unsigned>(std::max<std::size_t>(arrivals.size(), 1))));
  std::vector<std::thread> pool;
  for (unsigned t = 0; t < threads; ++t) pool.emplace_back(worker);
  for (std::thread &t : pool) t.join();
  if (failure) std::rethrow_exception(failure);
  std::vector<ArrivalResult> results;
  for (auto &arrival : by_arrival)
    for (auto &result : arrival) results.push_back(std::move(result));
  return results;
}

std::vector<CellSummary> summarize(const std::vector<ArrivalResult> &results) {
  std::vector<CellSummary> cells;
  std::map<std::tuple<std::string, double, std::string>, std::size_t> index;
  std::vector<std::vector<double>> percents, milliseconds;
  for (const ArrivalResult &r : results) {
    const auto key = std::make_tuple(r.path, r.rate, r.method);
    auto found = index.find(key);
    if (found == index.end()) {
      found = index.emplace(key, cells.size()).first;
      cells.push_back({r.path, r.method, r.rate});
      percents.emplace_back();
      milliseconds.emplace_back();
    }
    CellSummary &cell = cells[found->second];
    ++cell.arrivals;
    cell.registrations += r.registrations;
    cell.failures += r.failures;
    percents[found->second].push_back(r.end_point_percent);
    milliseconds[found->second].push_back(r.median_ms);
  }
  for (std::size_t k = 0; k < cells.size(); ++k) {
    cells[k].median_percent = evaluation::median(percents[k]);
    cells[k].worst_percent = *std::max_element(percents[k].begin(), percents[k].end());
    cells[k].median_ms = evaluation::median(milliseconds[k]);
  }
  return cells;
}

}  // namespace contour_reg::experiment
