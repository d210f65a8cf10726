#pragma once
// Studies spread over many processes or machines: a command that has independent jobs
// writes its plan (one shell command per job), runs one job by its index, and merges the
// jobs' result files into the table a single run writes. A single run goes through the
// same result files, so the merged table is the single run's table.

#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace contour_reg::cli {

/// Keeps the tool's command line, for the plan's lines (main calls it first).
void rememberCommandLine(int argc, char **argv);

struct FanOutOptions {
  bool plan = false;               ///< write OUT/plan.txt and stop
  std::optional<std::size_t> job;  ///< run this job only
  bool merge = false;              ///< build the table from OUT's job results, run nothing
};

/// --plan, --job K, --merge (at most one of them).
void addFanOutOptions(CLI::App &command, FanOutOptions &options);

/// Writes `folder`/plan.txt: line k runs job k (this command line, from this folder, without
/// --plan and with --job k), and tells on stderr how to run and merge it. Returns 0.
int writePlan(const std::string &folder, std::size_t jobs);

/// A job's numbers, written as "name value" lines beside its other outputs.
using JobRecord = std::map<std::string, double>;
void writeJobRecord(const std::string &path, const std::string &title, const JobRecord &record);
/// Reads a job record; throws io::ReadError naming the file (and line): a missing file says
/// which job has not run.
JobRecord readJobRecord(const std::string &path, const std::string &job);
/// The value `name` of a record, or a ReadError naming the file.
double recordValue(const JobRecord &record, const std::string &name, const std::string &path);
/// A value of a record that counts something (registrations, failures, scans): a whole number
/// from 0 to kMostCounted, or a ReadError naming the file and the value.
constexpr double kMostCounted = 1e15;
std::size_t recordCount(const JobRecord &record, const std::string &name, const std::string &path);

/// Tells a log (stderr that is not a terminal) that one job of `total` has finished: one
/// line per job, as a scheduler's log wants it. Silent on a terminal, where a bar shows progress.
void reportFinishedJob(std::size_t done, std::size_t total, const std::string &what);

}  // namespace contour_reg::cli
