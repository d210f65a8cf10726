#include "fan_out.h"

#include <unistd.h>

#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "contour_reg/io/scan_log.h"

namespace contour_reg::cli {

namespace {

std::vector<std::string> &commandLine() {
  static std::vector<std::string> line;
  return line;
}

// A word the shell takes as it is.
std::string shellQuoted(const std::string &word) {
  if (!word.empty() &&
      word.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-+=./,:@%") ==
          std::string::npos)
    return word;
  std::string quoted = "'";
  for (char c : word) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

}  // namespace

void rememberCommandLine(int argc, char **argv) {
  commandLine().assign(argv, argv + argc);
  std::error_code error;  // the tool as the jobs will find it: its absolute path
  const auto self = std::filesystem::read_symlink("/proc/self/exe", error);
  if (!error && !commandLine().empty()) commandLine()[0] = self.string();
}

void addFanOutOptions(CLI::App &command, FanOutOptions &options) {
  auto *plan = command.add_flag("--plan", options.plan,
                                "Write OUT/plan.txt, one shell command per independent job, and stop (for GNU "
                                "parallel, a Slurm array or any scheduler; docs/fan_out.md)");
  auto *job = command.add_option("--job", options.job, "Run job K of the plan only (0-based)");
  auto *merge =
      command.add_flag("--merge", options.merge, "Build the table from the jobs' results in OUT; run nothing");
  plan->excludes(job)->excludes(merge);
  job->excludes(merge);
}

int writePlan(const std::string &folder, std::size_t jobs) {
  const std::string path = (std::filesystem::path(folder) / "plan.txt").string();
  std::ofstream out(path);
  if (!out) throw io::ReadError(path + ": cannot write");
  const std::string here = std::filesystem::current_path().string();
  for (std::size_t k = 0; k < jobs; ++k) {
    out << "cd " << shellQuoted(here) << " &&";
    for (const std::string &word : commandLine())
      if (word != "--plan") out << ' ' << shellQuoted(word);
    out << " --job " << k << '\n';
  }
  out.flush();
  if (!out) throw io::ReadError(path + ": write failed");
  std::fprintf(stderr,
               "%zu jobs written to %s, one command per line. Run them, then the same command with --merge instead "
               "of --plan:\n  parallel --will-cite -j CORES < %s    (or a Slurm array: docs/fan_out.md)\n",
               jobs, path.c_str(), path.c_str());
  return 0;
}

void writeJobRecord(const std::string &path, const std::string &title, const JobRecord &record) {
  const std::string partial = path + ".partial";  // renamed when complete: a killed job leaves no record
  {
    std::ofstream out(partial);
    if (!out) throw io::ReadError(partial + ": cannot write");
    out << "# " << title << '\n';
    char value[64];
    for (const auto &[name, v] : record) {
      std::snprintf(value, sizeof value, "%.17g", v);
      out << name << ' ' << value << '\n';
    }
    out.flush();
    if (!out) throw io::ReadError(partial + ": write failed");
  }
  std::filesystem::rename(partial, path);
}

JobRecord readJobRecord(const std::string &path, const std::string &job) {
  std::ifstream in(path);
  if (!in) throw io::ReadError(path + ": no result of job " + job + " (has it run?)");
  JobRecord record;
  std::string line;
  for (std::size_t number = 1; std::getline(in, line); ++number) {
    if (line.empty() || line[0] == '#') continue;
    // NAME VALUE, the value as writeJobRecord wrote it (%.17g: nan and inf too).
    std::istringstream fields(line);
    std::string name, text, rest;
    double value = 0.0;
    bool parsed = fields >> name >> text && !(fields >> rest);
    if (parsed) {
      const std::from_chars_result read = std::from_chars(text.data(), text.data() + text.size(), value);
      parsed = read.ec == std::errc() && read.ptr == text.data() + text.size();
    }
    if (!parsed) throw io::ReadError(path + ":" + std::to_string(number) + ": expected NAME VALUE: " + line);
    record[name] = value;
  }
  return record;
}

double recordValue(const JobRecord &record, const std::string &name, const std::string &path) {
  const auto found = record.find(name);
  if (found == record.end()) throw io::ReadError(path + ": no value '" + name + "'");
  return found->second;
}

std::size_t recordCount(const JobRecord &record, const std::string &name, const std::string &path) {
  const double value = recordValue(record, name, path);
  if (!(value >= 0.0 && value <= kMostCounted && value == std::floor(value))) {
    char shown[64];
    std::snprintf(shown, sizeof shown, "%.17g", value);
    throw io::ReadError(path + ": '" + name + "' is not a count: " + shown);
  }
  return static_cast<std::size_t>(value);
}

void reportFinishedJob(std::size_t done, std::size_t total, const std::string &what) {
  if (isatty(STDERR_FILENO)) return;
  std::fprintf(stderr, "job %zu/%zu done: %s\n", done, total, what.c_str());
}

}  // namespace contour_reg::cli
