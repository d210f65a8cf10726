// contour_reg compare: several methods on the same scans, one table of accuracy and speed.
#include <algorithm>
#include <atomic>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <thread>

#include <pcl/console/print.h>

#include "cli_options.h"
#include "commands.h"
#include "contour_reg/drawing/debug_images.h"
#include "contour_reg/evaluation/metrics.h"
#include "contour_reg/io/pose2d.h"
#include "contour_reg/io/read_log.h"
#include "contour_reg/io/trajectory.h"
#include "contour_reg/odometry/odometry.h"
#include "fan_out.h"

namespace contour_reg::cli {

namespace {

namespace fs = std::filesystem;

const char *kWheelOdometry = "wheel-odometry";

struct CompareOptions {
  std::vector<std::string> inputs, ground_truths, relations;
  std::vector<std::string> methods = {"contour", "contour+icp", "icp", "icp-pl", "ndt2d"};
  std::string out;
  std::string guess = "zero";
  ChainOptions chain;
  bool log_poses = false;  // the log's own poses are the ground truth, hidden from the methods
  unsigned jobs = 0;
  double local_dt = 5.0;
  io::LogReadOptions read;
  MethodOptions method_options;
  FanOutOptions fan_out;
};

struct Input {
  std::string name;  // file stem, for the table and file names
  io::ScanLog log;
  std::optional<io::Trajectory> ground_truth;
  std::optional<std::vector<io::Relation>> relations;
  bool by_scan_order = false;  // with --log-poses: the log's stamps do not tell its scans apart
};

// `trajectory` with its k-th pose stamped k: poses paired by their order, not by their stamps.
io::Trajectory stampedInOrder(io::Trajectory trajectory) {
  for (std::size_t k = 0; k < trajectory.size(); ++k) trajectory[k].stamp = static_cast<double>(k);
  return trajectory;
}

struct Row {
  std::string input, method;
  std::size_t registrations = 0, failures = 0, degenerate = 0;
  double median_ms = 0.0, p95_ms = 0.0;
  evaluation::Evaluation evaluation;
  io::Trajectory trajectory;
};

// A reference given on the command line (by position), or one found beside the input.
std::string reference(const std::vector<std::string> &given, std::size_t k, const std::string &input,
                      const std::string &suffix) {
  if (k < given.size()) return given[k];
  const fs::path beside = fs::path(input).parent_path() / (logStem(input) + suffix);
  return fs::exists(beside) ? beside.string() : std::string();
}

std::string cell(const std::optional<double> &value, const char *format) {
  if (!value) return "-";
  char text[64];
  std::snprintf(text, sizeof text, format, *value);
  return text;
}

void writeTables(const std::vector<Row> &rows, const CompareOptions &options) {
  const std::string table_path = (fs::path(options.out) / "table.md").string();
  const std::string csv_path = (fs::path(options.out) / "results.csv").string();
  std::FILE *table = std::fopen(table_path.c_str(), "w");
  std::FILE *csv = std::fopen(csv_path.c_str(), "w");
  if (!table || !csv) {
    if (table) std::fclose(table);
    if (csv) std::fclose(csv);
    throw io::ReadError(options.out + ": cannot write table.md / results.csv");
  }
  char header[512];
  std::snprintf(
      header, sizeof header,
      "| input | method | failed / registrations | local rel. transl. m | local rel. rot. deg | all rel. transl. m "
      "| end-point %% of path | drift %% (10 m) | ATE m | median ms | p95 ms |\n"
      "|---|---|---|---|---|---|---|---|---|---|---|\n");
  std::string text = header;
  std::fprintf(csv,
               "input,method,registrations,failures,degenerate,local_relations,local_translation_mean_m,"
               "local_translation_std_m,local_rotation_mean_deg,local_rotation_std_deg,all_relations,"
               "all_translation_mean_m,all_rotation_mean_deg,end_point_error_m,end_point_percent,drift_percent,"
               "ate_m,median_ms,p95_ms\n");
  for (const Row &row : rows) {
    const auto &e = row.evaluation;
    auto opt = [](bool has, double v) { return has ? std::optional<double>(v) : std::nullopt; };
    const bool rel = e.relations_local.has_value();
    const bool gt = e.end_point.has_value();
    const bool timed = row.method != kWheelOdometry;
    char line[1024];
    std::snprintf(line, sizeof line, "| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |\n", row.input.c_str(),
                  row.method.c_str(),
                  timed ? (std::to_string(row.failures) + " / " + std::to_string(row.registrations)).c_str() : "-",
                  rel ? (cell(e.relations_local->translation_mean, "%.3f") + " +- " +
                         cell(e.relations_local->translation_std, "%.3f"))
                            .c_str()
                      : "-",
                  cell(opt(rel, rel ? e.relations_local->rotation_mean : 0), "%.2f").c_str(),
                  cell(opt(rel, rel ? e.relations_all->translation_mean : 0), "%.3f").c_str(),
                  cell(opt(gt, gt ? e.end_point->percent : 0), "%.2f").c_str(),
                  cell(opt(e.drift.has_value(), e.drift ? e.drift->mean_percent : 0), "%.2f").c_str(),
                  cell(e.ate, "%.3f").c_str(), cell(opt(timed, row.median_ms), "%.3f").c_str(),
                  cell(opt(timed, row.p95_ms), "%.3f").c_str());
    text += line;
    std::fprintf(csv, "%s,%s,%zu,%zu,%zu,%zu,%.6f,%.6f,%.4f,%.4f,%zu,%.6f,%.4f,%.6f,%.4f,%.4f,%.6f,%.4f,%.4f\n",
                 row.input.c_str(), row.method.c_str(), row.registrations, row.failures, row.degenerate,
                 rel ? e.relations_local->count : 0, rel ? e.relations_local->translation_mean : NAN,
                 rel ? e.relations_local->translation_std : NAN, rel ? e.relations_local->rotation_mean : NAN,
                 rel ? e.relations_local->rotation_std : NAN, rel ? e.relations_all->count : 0,
                 rel ? e.relations_all->translation_mean : NAN, rel ? e.relations_all->rotation_mean : NAN,
                 gt ? e.end_point->error : NAN, gt ? e.end_point->percent : NAN, e.drift ? e.drift->mean_percent : NAN,
                 e.ate.value_or(NAN), timed ? row.median_ms : NAN, timed ? row.p95_ms : NAN);
  }
  std::fputs(text.c_str(), table);
  std::fclose(table);
  std::fclose(csv);
  std::fputs(text.c_str(), stdout);
  std::printf("\nwritten: %s, %s, one TUM trajectory per input and method\n", table_path.c_str(), csv_path.c_str());
}

// The jobs of a comparison: every method on every input, inputs first.
struct Job {
  std::size_t input;
  std::string method;
};

std::vector<Job> planJobs(const CompareOptions &options) {
  std::vector<Job> jobs;
  for (std::size_t k = 0; k < options.inputs.size(); ++k)
    for (const std::string &method : options.methods) jobs.push_back({k, method});
  return jobs;
}

Input loadInput(const CompareOptions &options, std::size_t k) {
  Input input;
  input.name = logStem(options.inputs[k]);
  input.log = io::readLog(options.inputs[k], options.read);
  printReadReport(input.log);
  warnOfMissingOdometry(input.log, options.guess, options.read);
  if (options.log_poses) {
    // The log's poses (the corrected poses of the Radish logs) are the reference: the methods
    // run on the scans alone, so that neither a guess, the deskewing nor the fusion with the
    // wheels reads them.
    input.ground_truth = odometry::wheelOdometry(input.log);
    if (input.ground_truth->size() < 2)
      throw io::ReadError(options.inputs[k] + ": --log-poses, but the log has no poses of its own" +
                          (options.read.wheel_odometry ? "" : " (read with --no-wheel-odometry)"));
    io::leaveOutWheelOdometry(input.log);
    // A log that kept its stamps to six digits, or none, has poses and trajectories of one
    // pose per scan: they are paired by scan order.
    if (const std::size_t repeated = evaluation::nonIncreasingStamps(*input.ground_truth); repeated > 0) {
      input.by_scan_order = true;
      input.ground_truth = stampedInOrder(*input.ground_truth);
      std::fprintf(stderr,
                   "note: %s: %zu of %zu scans are stamped no later than the one before: the trajectories are "
                   "paired with the log's poses by scan order\n",
                   options.inputs[k].c_str(), repeated, input.log.entries.size());
    }
  } else if (const std::string gt = reference(options.ground_truths, k, options.inputs[k], ".gt.tum"); !gt.empty()) {
    input.ground_truth = io::readTum(gt);
  }
  if (const std::string rel = reference(options.relations, k, options.inputs[k], ".relations"); !rel.empty())
    input.relations = io::readRelations(rel);
  std::fprintf(stderr, "%s: %zu scans%s%s\n", options.inputs[k].c_str(), input.log.entries.size(),
               !input.ground_truth ? ""
               : options.log_poses ? ", ground truth: the log's poses"
                                   : ", ground truth",
               input.relations ? ", relations" : "");
  return input;
}

// A job's outputs: its trajectory and its record of counts and times.
std::string trajectoryPath(const CompareOptions &options, const std::string &input, const std::string &method) {
  return (fs::path(options.out) / (input + "." + method + ".tum")).string();
}
std::string recordPath(const CompareOptions &options, const std::string &input, const std::string &method) {
  return (fs::path(options.out) / "jobs" / (input + "." + method + ".txt")).string();
}

// Runs one method over one input and writes the job's outputs. `progress` gets the scans done.
void runJob(const CompareOptions &options, const Input &input, const std::string &method,
            const std::function<void(std::size_t, std::size_t)> &progress) {
  auto matcher = odometry::makeScanMatcher(method, options.method_options.settings());
  odometry::OdometryOptions run_options = options.chain.runOptions(options.guess);
  run_options.progress = progress;
  const odometry::OdometryRun run = odometry::runOdometry(input.log, *matcher, run_options);
  io::writeTum(trajectoryPath(options, input.name, method), run.trajectory,
               odometry::frameDescription(run.frame, input.log));
  fs::create_directories(fs::path(options.out) / "jobs");
  writeJobRecord(recordPath(options, input.name, method), "contour_reg compare job: " + input.name + " " + method,
                 {{"registrations", double(run.stats.registrations)},
                  {"failures", double(run.stats.failures)},
                  {"degenerate", double(run.stats.degenerate)},
                  {"median_ms", percentile(run.stats.milliseconds, 0.5)},
                  {"p95_ms", percentile(run.stats.milliseconds, 0.95)}});
}

// A job's row of the table, from its outputs.
Row readRow(const CompareOptions &options, const Input &input, const std::string &method) {
  const std::string path = recordPath(options, input.name, method);
  const JobRecord record = readJobRecord(path, input.name + " " + method);
  Row row;
  row.input = input.name;
  row.method = method;
  row.registrations = recordCount(record, "registrations", path);
  row.failures = recordCount(record, "failures", path);
  row.degenerate = recordCount(record, "degenerate", path);
  row.median_ms = recordValue(record, "median_ms", path);
  row.p95_ms = recordValue(record, "p95_ms", path);
  row.trajectory = io::readTum(trajectoryPath(options, input.name, method));
  if (input.by_scan_order && row.trajectory.size() == input.ground_truth->size())
    row.trajectory = stampedInOrder(std::move(row.trajectory));
  row.evaluation = evaluation::evaluate(row.trajectory, input.ground_truth ? &*input.ground_truth : nullptr,
                                        input.relations ? &*input.relations : nullptr, options.local_dt);
  return row;
}

// Runs every job on the cores of this machine; returns the number of threads used.
unsigned runJobs(const CompareOptions &options, const std::vector<Input> &inputs, const std::vector<Job> &jobs) {
  std::atomic<std::size_t> next{0}, finished{0};
  std::mutex print;
  // Progress over the scans of every job together.
  std::size_t all_scans = 0;
  for (const Job &job : jobs) all_scans += inputs[job.input].log.entries.size();
  std::atomic<std::size_t> scans_done{0};
  ProgressBar progress("compare");
  auto worker = [&]() {
    for (std::size_t j = next++; j < jobs.size(); j = next++) {
      const Input &input = inputs[jobs[j].input];
      std::size_t counted = 0;  // of this job's scans
      runJob(options, input, jobs[j].method, [&](std::size_t done, std::size_t) {
        const std::size_t now = scans_done += done - counted;
        counted = done;
        std::lock_guard<std::mutex> lock(print);
        progress(now, all_scans);
      });
      std::lock_guard<std::mutex> lock(print);
      reportFinishedJob(++finished, jobs.size(), input.name + " " + jobs[j].method);
    }
  };
  const unsigned threads =
      std::max(1u, std::min<unsigned>(options.jobs ? options.jobs : std::thread::hardware_concurrency(),
                                      static_cast<unsigned>(jobs.size())));
  std::vector<std::thread> pool;
  for (unsigned t = 0; t < threads; ++t) pool.emplace_back(worker);
  for (std::thread &t : pool) t.join();
  progress.finish();
  return threads;
}

int runCompare(const CompareOptions &options) {
  pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
  const std::vector<Job> jobs = planJobs(options);
  if (options.fan_out.plan) return writePlan(options.out, jobs.size());
  if (options.fan_out.job) {
    const Job &job = jobs[*options.fan_out.job];
    runJob(options, loadInput(options, job.input), job.method, {});
    reportFinishedJob(*options.fan_out.job + 1, jobs.size(), logStem(options.inputs[job.input]) + " " + job.method);
    return 0;
  }
  std::vector<Input> inputs;
  for (std::size_t k = 0; k < options.inputs.size(); ++k) inputs.push_back(loadInput(options, k));
  const unsigned threads = options.fan_out.merge ? 0 : runJobs(options, inputs, jobs);
  std::vector<Row> rows;
  for (const Job &job : jobs) rows.push_back(readRow(options, inputs[job.input], job.method));
  // A reference that covers nothing gives "-" cells; say why.
  for (const Input &input : inputs) {
    const Row *any = nullptr;
    for (const Row &row : rows)
      if (row.input == input.name) any = &row;
    if (!any) continue;
    const evaluation::Evaluation &e = any->evaluation;
    if (e.estimate_stamps_not_increasing > 0) {
      std::fprintf(stderr, "warning: %s, the estimate: %s\n", input.name.c_str(),
                   stampsDoNotIncrease(e.estimate_stamps_not_increasing, e.estimate_poses, "").c_str());
      continue;
    }
    if (e.ground_truth_stamps_not_increasing > 0)
      std::fprintf(
          stderr, "warning: %s, the ground truth: %s\n", input.name.c_str(),
          stampsDoNotIncrease(e.ground_truth_stamps_not_increasing, input.ground_truth->size(), "ground-truth ")
              .c_str());
    else if (input.ground_truth && !e.ate)
      std::fprintf(stderr,
                   "warning: %s: the ground truth shares %zu stamps with the estimate: no ground-truth metric\n",
                   input.name.c_str(), e.matched_poses);
    if (input.relations && !e.relations_local)
      std::fprintf(stderr, "warning: %s: the estimate covers none of the %zu relations: no relation metric\n",
                   input.name.c_str(), input.relations->size());
  }

  // The log's own wheel odometry, where it has it, as a baseline row (with --log-poses the
  // log's poses are the ground truth, and the inputs hold none).
  for (const Input &input : inputs) {
    const io::Trajectory wheel = odometry::wheelOdometry(input.log);
    if (wheel.size() < 2) continue;
    Row row;
    row.input = input.name;
    row.method = kWheelOdometry;
    row.evaluation = evaluation::evaluate(wheel, input.ground_truth ? &*input.ground_truth : nullptr,
                                          input.relations ? &*input.relations : nullptr, options.local_dt);
    rows.push_back(row);
  }
  std::stable_sort(rows.begin(), rows.end(), [](const Row &a, const Row &b) { return a.input < b.input; });
  // Trajectory pictures where there is ground truth.
  for (const Input &input : inputs) {
    if (!input.ground_truth) continue;
    std::map<std::string, io::Trajectory> estimates;
    for (const Row &row : rows)
      if (row.input == input.name && row.method != kWheelOdometry) estimates[row.method] = row.trajectory;
    const std::string title = input.name + ": " + std::to_string(input.log.entries.size()) + " scans, guess " +
                              options.guess +
                              (options.chain.keyframes.match_keyframes ? ", keyframes" : ", scan to scan");
    drawing::writeImage((fs::path(options.out) / (input.name + ".trajectories.png")).string(),
                        drawing::drawTrajectories(estimates, *input.ground_truth, 1200, title));
  }
  std::printf("guess: %s; %s; ms = registration only\n\n", options.guess.c_str(),
              options.chain.keyframes.match_keyframes ? "keyframes" : "scan to scan");
  if (threads > 0) std::fprintf(stderr, "%u parallel jobs\n", threads);
  writeTables(rows, options);
  return 0;
}

}  // namespace

void addCompareCommand(CLI::App &app) {
  auto options = std::make_shared<CompareOptions>();
  CLI::App *command =
      app.add_subcommand("compare", "Run several methods on the same scans: one table of accuracy and speed");
  command->add_option("inputs", options->inputs, "CARMEN logs, ROS 1 or ROS 2 bags or PCD folders")
      ->required()
      ->check(CLI::ExistingPath);
  command->add_option("--methods", options->methods, "Methods to run")->check(methodCheck())->capture_default_str();
  command
      ->add_option("--gt", options->ground_truths,
                   "Ground truth TUM per input, in order (default: INPUT_STEM.gt.tum beside the input)")
      ->check(CLI::ExistingFile);
  command
      ->add_flag("--log-poses", options->log_poses,
                 "Score against the poses in each log (the corrected poses of the Radish logs) as ground truth; the "
                 "methods then run on the scans alone")
      ->excludes("--gt");
  command
      ->add_option("--relations", options->relations,
                   "Relations file per input, in order (default: INPUT_STEM.relations beside the input)")
      ->check(CLI::ExistingFile);
  command->add_option("--out", options->out, "Output folder")->required();
  addGuessOption(*command, options->guess);
  addChainOptions(*command, options->chain);
  command->add_option("--jobs,-j", options->jobs, "Parallel runs (default: one per core)");
  command->add_option("--local-dt", options->local_dt, "Relations at most this far apart are local (s)")
      ->capture_default_str()
      ->check(positive());
  addReadOptions(*command, options->read);
  addMethodOptions(*command, options->method_options);
  addFanOutOptions(*command, options->fan_out);
  command->callback([options]() {
    validateMethodOptions(options->method_options);
    if (options->log_poses && options->guess == "odom")
      throw CLI::ValidationError("--guess odom",
                                 "would start each registration from the log's poses, the ground truth of --log-poses");
    const std::size_t jobs = options->inputs.size() * options->methods.size();
    if (options->fan_out.job && *options->fan_out.job >= jobs)
      throw CLI::ValidationError("--job",
                                 "the plan has " + std::to_string(jobs) + " jobs (0-" + std::to_string(jobs - 1) + ")");
    prepareOutputFolder("--out", options->out);
    runCommand([&] { return runCompare(*options); });
  });
}

}  // namespace contour_reg::cli
