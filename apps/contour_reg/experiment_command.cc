// contour_reg experiment: the paper's experiment (Table 1) on the built-in office or any
// map: every path x LIDAR rate x arrival, each method on the same simulated scans.
#include <cstdio>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <sstream>

#include <pcl/console/print.h>

#include "cli_options.h"
#include "commands.h"
#include "contour_reg/drawing/debug_images.h"
#include "contour_reg/experiment/paper_experiment.h"
#include "contour_reg/io/trajectory.h"
#include "contour_reg/simulation/paths.h"
#include "contour_reg/simulation/simulated_run.h"
#include "fan_out.h"
#include "scenario.h"

namespace contour_reg::cli {

namespace {

namespace fs = std::filesystem;

struct ExperimentOptions {
  std::string out;
  std::vector<std::string> paths = simulation::pathShapes();
  std::vector<double> rates = {5.0, 2.0, 1.0};
  std::vector<std::string> methods = {"contour", "icp", "ndt2d"};
  int arrivals = 10;
  unsigned seed = 1, jobs = 0;
  std::string guess = "zero";
  bool deskew = true, wheel_fusion = true;
  odometry::WheelNoise wheel_noise;
  ScenarioOptions scenario;
  MethodOptions method_options;
  FanOutOptions fan_out;
};

std::string rateName(double rate) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", rate);
  return text;
}

std::string describe(const ExperimentOptions &options, const Scenario &scenario,
                     const experiment::ExperimentSettings &s) {
  std::ostringstream text;
  text << "Map " << scenario.map_name << "; LIDAR " << s.run.lidar.name << " (" << s.run.lidar.beams << " beams, "
       << s.run.lidar.range_max << " m, noise " << s.run.lidar.range_noise << " m); " << options.scenario.motion
       << " at " << s.run.speed << " m/s; " << options.arrivals << " arrivals per cell (seeds " << options.seed << ".."
       << options.seed + static_cast<unsigned>(std::max(options.arrivals, 1)) - 1 << "); guess " << options.guess
       << ". Paths:";
  for (const auto &[name, waypoints] : scenario.paths) {
    double length = 0.0;
    for (std::size_t k = 1; k < waypoints.size(); ++k) length += (waypoints[k] - waypoints[k - 1]).norm();
    char item[64];
    std::snprintf(item, sizeof item, " %s %.1f m;", name.c_str(), length);
    text << item;
  }
  return text.str();
}

void writeTables(const ExperimentOptions &options, const std::string &description,
                 const std::vector<experiment::ArrivalResult> &results) {
  const std::vector<experiment::CellSummary> cells = experiment::summarize(results);
  std::map<std::tuple<double, std::string, std::string>, const experiment::CellSummary *> by_key;
  for (const auto &cell : cells) by_key[{cell.rate, cell.method, cell.path}] = &cell;
  std::vector<std::string> methods = options.methods;
  methods.push_back(experiment::kWheelOdometry);

  std::ostringstream table;
  table << "# Experiment: end-point error over path length\n\n" << description << "\n\n";
  table << "Median over the arrivals of |end position error| / path length, % (worst arrival in brackets). "
           "The paper's row is its Table 1 (Gazebo, Willow Garage map).\n\n";
  char value[64];
  auto header = [&]() {
    table << "| LIDAR rate | method |";
    for (const std::string &path : options.paths) table << " " << path << " |";
    table << "\n|---|---|";
    for (std::size_t k = 0; k < options.paths.size(); ++k) table << "---|";
    table << "\n";
  };
  // One table row: the cell of every path, written into `value` by `format`.
  auto row = [&](double rate, const std::string &method,
                 const std::function<void(const experiment::CellSummary &)> &format) {
    table << "| " << rateName(rate) << " Hz | " << method << " |";
    for (const std::string &path : options.paths) {
      const auto found = by_key.find({rate, method, path});
      if (found == by_key.end()) {
        table << " - |";
        continue;
      }
      format(*found->second);
      table << value;
    }
    table << "\n";
  };
  header();
  for (double rate : options.rates) {
    bool paper_row = false;
    for (const std::string &path : options.paths) paper_row |= experiment::paperMedianPercent(path, rate).has_value();
    if (paper_row) {
      table << "| " << rateName(rate) << " Hz | paper |";
      for (const std::string &path : options.paths) {
        const auto paper = experiment::paperMedianPercent(path, rate);
        if (paper) std::snprintf(value, sizeof value, " %.1f |", *paper);
        table << (paper ? value : " - |");
      }
      table << "\n";
    }
    for (const std::string &method : methods)
      row(rate, method, [&](const experiment::CellSummary &cell) {
        std::snprintf(value, sizeof value, " %.2f (%.2f) |", cell.median_percent, cell.worst_percent);
      });
  }
  table << "\nFailed registrations / registrations over all arrivals, and the median ms per registration:\n\n";
  header();
  for (double rate : options.rates)
    for (const std::string &method : options.methods)
      row(rate, method, [&](const experiment::CellSummary &cell) {
        std::snprintf(value, sizeof value, " %zu / %zu, %.2f ms |", cell.failures, cell.registrations, cell.median_ms);
      });

  const fs::path out(options.out);
  std::FILE *file = std::fopen((out / "table.md").string().c_str(), "w");
  std::FILE *csv = std::fopen((out / "arrivals.csv").string().c_str(), "w");
  if (!file || !csv) {
    if (file) std::fclose(file);
    if (csv) std::fclose(csv);
    throw io::ReadError(options.out + ": cannot write table.md / arrivals.csv");
  }
  std::fputs(table.str().c_str(), file);
  std::fclose(file);
  std::fprintf(csv,
               "path,rate_hz,arrival,method,path_length_m,scans,registrations,failures,end_point_error_m,"
               "end_point_percent,median_ms\n");
  for (const auto &r : results)
    std::fprintf(csv, "%s,%g,%d,%s,%.4f,%zu,%zu,%zu,%.6f,%.4f,%.4f\n", r.path.c_str(), r.rate, r.arrival,
                 r.method.c_str(), r.path_length, r.scans, r.registrations, r.failures, r.end_point_error,
                 r.end_point_percent, r.median_ms);
  std::fclose(csv);
  std::fputs(table.str().c_str(), stdout);
  std::printf("\nwritten in %s: table.md, arrivals.csv, map.png, trajectories/\n", options.out.c_str());
}

std::string arrivalName(const experiment::Arrival &arrival) {
  return arrival.path + "-" + rateName(arrival.rate) + "hz-a" + std::to_string(arrival.arrival);
}

// One arrival's outputs: a record of every method's numbers and, for the first arrival, the
// trajectories its pictures show.
fs::path arrivalFile(const ExperimentOptions &options, const experiment::Arrival &arrival, const std::string &suffix) {
  return fs::path(options.out) / "jobs" / (arrivalName(arrival) + suffix);
}

void writeArrival(const ExperimentOptions &options, const experiment::Arrival &arrival,
                  const std::vector<experiment::ArrivalResult> &results) {
  fs::create_directories(fs::path(options.out) / "jobs");
  JobRecord record{{"path_length_m", results.front().path_length}, {"scans", double(results.front().scans)}};
  for (const auto &r : results) {
    record[r.method + ".registrations"] = double(r.registrations);
    record[r.method + ".failures"] = double(r.failures);
    record[r.method + ".end_point_error_m"] = r.end_point_error;
    record[r.method + ".end_point_percent"] = r.end_point_percent;
    record[r.method + ".median_ms"] = r.median_ms;
    if (arrival.arrival == 0) io::writeTum(arrivalFile(options, arrival, "." + r.method + ".tum").string(), r.estimate);
  }
  if (arrival.arrival == 0)
    io::writeTum(arrivalFile(options, arrival, ".gt.tum").string(), results.front().ground_truth);
  writeJobRecord(arrivalFile(options, arrival, ".txt").string(), "contour_reg experiment job: " + arrivalName(arrival),
                 record);
}

std::vector<experiment::ArrivalResult> readArrival(const ExperimentOptions &options,
                                                   const experiment::Arrival &arrival) {
  const std::string path = arrivalFile(options, arrival, ".txt").string();
  const JobRecord record = readJobRecord(path, arrivalName(arrival));
  std::vector<std::string> methods = options.methods;
  methods.push_back(experiment::kWheelOdometry);
  const io::Trajectory ground_truth =
      arrival.arrival == 0 ? io::readTum(arrivalFile(options, arrival, ".gt.tum").string()) : io::Trajectory();
  std::vector<experiment::ArrivalResult> results;
  for (const std::string &method : methods) {
    experiment::ArrivalResult r;
    r.path = arrival.path;
    r.rate = arrival.rate;
    r.arrival = arrival.arrival;
    r.method = method;
    r.path_length = recordValue(record, "path_length_m", path);
    r.scans = recordCount(record, "scans", path);
    r.registrations = recordCount(record, method + ".registrations", path);
    r.failures = recordCount(record, method + ".failures", path);
    r.end_point_error = recordValue(record, method + ".end_point_error_m", path);
    r.end_point_percent = recordValue(record, method + ".end_point_percent", path);
    r.median_ms = recordValue(record, method + ".median_ms", path);
    if (arrival.arrival == 0) {
      r.estimate = io::readTum(arrivalFile(options, arrival, "." + method + ".tum").string());
      r.ground_truth = ground_truth;
    }
    results.push_back(std::move(r));
  }
  return results;
}

int runExperiment(const ExperimentOptions &options) {
  pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
  const Scenario scenario = loadScenario(options.scenario, options.paths);
  for (const auto &[name, waypoints] : scenario.paths)
    for (double rate : options.rates)
      simulation::checkRunSize(simulation::pathLength(waypoints), runSettings(options.scenario, rate, options.seed));
  std::error_code error;
  fs::create_directories(fs::path(options.out) / "trajectories", error);
  if (!fs::is_directory(options.out)) throw io::ReadError(options.out + ": cannot create the output folder");

  experiment::ExperimentSettings settings;
  settings.methods = options.methods;
  settings.rates = options.rates;
  settings.arrivals = options.arrivals;
  settings.seed = options.seed;
  settings.run = runSettings(options.scenario, options.rates.front(), options.seed);
  settings.matcher = options.method_options.settings();
  settings.guess = guessSource(options.guess);
  settings.deskew = options.deskew;
  settings.wheel_fusion = options.wheel_fusion;
  settings.wheel_noise = options.wheel_noise;
  settings.jobs = options.jobs;
  const std::vector<experiment::Arrival> arrivals = experiment::planArrivals(scenario.paths, settings);
  if (options.fan_out.plan) return writePlan(options.out, arrivals.size());
  if (options.fan_out.job) {
    if (*options.fan_out.job >= arrivals.size())
      throw CLI::ValidationError("--job", "the plan has " + std::to_string(arrivals.size()) + " jobs (0-" +
                                              std::to_string(arrivals.size() - 1) + ")");
    const experiment::Arrival &arrival = arrivals[*options.fan_out.job];
    writeArrival(options, arrival, experiment::runArrival(scenario.world, scenario.paths, settings, arrival));
    reportFinishedJob(*options.fan_out.job + 1, arrivals.size(), arrivalName(arrival));
    return 0;
  }
  const std::string description = describe(options, scenario, settings);
  if (!options.fan_out.merge) {
    ProgressBar progress("experiment");
    settings.progress = [&](std::size_t done, std::size_t all) {
      progress(done, all);
      reportFinishedJob(done, all, "arrival");
    };
    std::fprintf(stderr, "%s\n", description.c_str());
    const auto results = experiment::runExperiment(scenario.world, scenario.paths, settings);
    progress.finish();
    const std::size_t per_arrival = options.methods.size() + 1;
    for (std::size_t k = 0; k < arrivals.size(); ++k)
      writeArrival(options, arrivals[k],
                   std::vector<experiment::ArrivalResult>(results.begin() + k * per_arrival,
                                                          results.begin() + (k + 1) * per_arrival));
  }
  std::vector<experiment::ArrivalResult> results;
  for (const experiment::Arrival &arrival : arrivals)
    for (auto &r : readArrival(options, arrival)) results.push_back(std::move(r));
  drawing::writeImage((fs::path(options.out) / "map.png").string(), drawing::drawWorld(scenario.world, scenario.paths));

  // Trajectories of the first arrival of every path and rate.
  std::map<std::pair<std::string, double>, std::map<std::string, io::Trajectory>> estimates;
  std::map<std::pair<std::string, double>, io::Trajectory> truths;
  for (const auto &r : results) {
    if (r.arrival != 0) continue;
    estimates[{r.path, r.rate}][r.method] = r.estimate;
    truths[{r.path, r.rate}] = r.ground_truth;
  }
  for (const auto &[key, by_method] : estimates) {
    const std::string name = key.first + "-" + rateName(key.second) + "hz.png";
    const std::string title = "path " + key.first + " at " + rateName(key.second) + " Hz, map " + scenario.map_name +
                              ", " + settings.run.lidar.name + ", first arrival (seed " + std::to_string(options.seed) +
                              ")";
    drawing::writeImage((fs::path(options.out) / "trajectories" / name).string(),
                        drawing::drawTrajectories(by_method, truths[key], 1200, title));
  }
  writeTables(options, description, results);
  return 0;
}

}  // namespace

void addExperimentCommand(CLI::App &app) {
  auto options = std::make_shared<ExperimentOptions>();
  CLI::App *command = app.add_subcommand(
      "experiment", "The paper's experiment: paths x LIDAR rates x arrivals, each method on the same simulated scans");
  command->add_option("--out", options->out, "Output folder")->required();
  command->add_option("--paths", options->paths, "Path shapes (or names in --paths-file)")->capture_default_str();
  command->add_option("--rates", options->rates, "LIDAR rates (Hz)")->capture_default_str()->check(positive());
  command->add_option("--arrivals", options->arrivals, "Runs per path and rate, each with its own seed")
      ->capture_default_str()
      ->check(positive());
  command->add_option("--methods", options->methods, "Methods to run")->check(methodCheck())->capture_default_str();
  command->add_option("--seed", options->seed, "Seed of the first arrival")->capture_default_str();
  command->add_option("--jobs,-j", options->jobs, "Parallel arrivals (default: one per core)");
  addGuessOption(*command, options->guess);
  addDeskewOption(*command, options->deskew);
  addWheelFusionOptions(*command, options->wheel_fusion, options->wheel_noise);
  addScenarioOptions(*command, options->scenario);
  addMethodOptions(*command, options->method_options);
  addFanOutOptions(*command, options->fan_out);
  command->callback([options]() {
    validateMethodOptions(options->method_options);
    prepareOutputFolder("--out", options->out);
    runCommand([&] { return runExperiment(*options); });
  });
}

}  // namespace contour_reg::cli
