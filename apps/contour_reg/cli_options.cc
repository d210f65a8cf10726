#include "cli_options.h"

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <system_error>

#include "contour_reg/core/contour_features.h"
#include "contour_reg/core/registration.h"
#include "contour_reg/core/transform_estimation.h"
#include "contour_reg/io/pose2d.h"
#include "contour_reg/io/trajectory.h"

namespace contour_reg::cli {

std::string printed(const char *format, ...) {
  va_list args, again;
  va_start(args, format);
  va_copy(again, args);
  std::string text(static_cast<std::size_t>(std::max(0, std::vsnprintf(nullptr, 0, format, args))), '\0');
  va_end(args);
  std::vsnprintf(text.data(), text.size() + 1, format, again);
  va_end(again);
  return text;
}

void printReadReport(const io::ScanLog &log) {
  for (const std::string &problem : log.report.problems) std::fprintf(stderr, "warning: %s\n", problem.c_str());
  if (log.report.skipped > log.report.problems.size())
    std::fprintf(stderr, "warning: %s: %zu bad lines skipped in all\n", log.source.c_str(), log.report.skipped);
  if (log.report.reordered > 0)
    std::fprintf(stderr, "note: %s: %zu scans were out of stamp order and were sorted\n", log.source.c_str(),
                 log.report.reordered);
}

void addScanPairOptions(CLI::App &command, ScanPair &pair, const std::string &scan_help) {
  command.add_option("input", pair.input, "CARMEN log, ROS 1 or ROS 2 bag or PCD folder")
      ->required()
      ->check(CLI::ExistingPath);
  command.add_option("--scan", pair.scan, scan_help)->capture_default_str()->check(nonNegative());
  command.add_option("--to", pair.to, "Target scan of the pair (default: the scan before)")->check(nonNegative());
}

void checkScanPair(const ScanPair &pair) {
  if (pair.scan == 0 && pair.to < 0) throw CLI::ValidationError("--scan", "scan 0 has no scan before it: give --to");
}

bool readScanPair(const ScanPair &pair, const io::LogReadOptions &read, io::ScanLog &log) {
  log = io::readLog(pair.input, read);
  printReadReport(log);
  const int count = static_cast<int>(log.entries.size());
  if (pair.scan < count && pair.target() < count) return true;
  std::fprintf(stderr, "error: --scan %d, --to %d: %s has scans 0..%d\n", pair.scan, pair.target(), pair.input.c_str(),
               count - 1);
  return false;
}

void addReferenceOptions(CLI::App &command, ReferenceOptions &options, const std::string &reference_help) {
  CLI::Option *reference = addMotionOption(command, "--reference", options.motion, reference_help);
  CLI::Option *log_poses = command.add_flag(
      "--log-poses", options.log_poses,
      "The pair's true motion from the log's own poses (the corrected poses of the Radish logs; a raw log's "
      "wheel odometry), as --reference");
  CLI::Option *truth = command
                           .add_option("--gt", options.ground_truth,
                                       "The pair's true motion from this TUM ground truth, interpolated at the "
                                       "scans' stamps, as --reference")
                           ->check(CLI::ExistingFile);
  reference->excludes(log_poses)->excludes(truth);
  log_poses->excludes(reference)->excludes(truth);
  truth->excludes(reference)->excludes(log_poses);
}

std::optional<io::Pose2D> referenceFromPoses(const ReferenceOptions &options, const ScanPair &pair,
                                             const io::ScanLog &log) {
  const io::LogEntry &a = log.entries[std::size_t(pair.target())], &b = log.entries[std::size_t(pair.scan)];
  std::optional<io::Pose2D> target, source;
  std::string from = options.ground_truth;
  if (options.log_poses) {
    target = a.odometry;
    source = b.odometry;
    from = pair.input + "'s poses";
  } else {
    std::string why;
    const auto poses = groundTruthAtScans(options.ground_truth, log, why);
    if (!poses) {
      std::fprintf(stderr, "error: %s\n", why.c_str());
      return std::nullopt;
    }
    target = (*poses)[std::size_t(pair.target())];
    source = (*poses)[std::size_t(pair.scan)];
  }
  if (target && source) return io::between(*target, *source);
  std::fprintf(stderr, "error: %s: no pose at scan %d (stamp %.6f s) or scan %d (stamp %.6f s)\n", from.c_str(),
               pair.target(), a.scan.stamp, pair.scan, b.scan.stamp);
  return std::nullopt;
}

Apart apart(const Eigen::Matrix3d &a, const Eigen::Matrix3d &b) {
  return {(a.topRightCorner<2, 1>() - b.topRightCorner<2, 1>()).norm(),
          std::abs(std::remainder(yawOf(a) - yawOf(b), 2 * M_PI)) * 180 / M_PI};
}

void toRobotFrame(odometry::MatchResult &result, const io::Pose2D &mounting) {
  const auto motion = [&](const Eigen::Matrix3d &laser) {
    return io::toMatrix(io::robotMotion(io::toPose(laser), mounting));
  };
  const auto covariance = [&](const Eigen::Matrix3d &laser_covariance, const Eigen::Matrix3d &laser) {
    return io::robotCovariance(laser_covariance, io::toPose(laser), mounting);
  };
  result.covariance = covariance(result.covariance, result.transform);
  result.transform = motion(result.transform);
  if (result.rejected) result.rejected = motion(*result.rejected);
  for (RejectedMotion &alternative : result.alternatives) {
    alternative.covariance = covariance(alternative.covariance, alternative.transform);
    alternative.transform = motion(alternative.transform);
  }
}

std::string beamsRead(const io::LogReadOptions &read) {
  return read.beam_step > 1 ? " (one beam in " + std::to_string(read.beam_step) + ")" : "";
}

std::string stampsDoNotIncrease(std::size_t count, std::size_t poses, const char *which) {
  return printed(
      "%zu of its %zu stamps are no later than the one before: they do not tell its poses apart, and no "
      "%smetric is given",
      count, poses, which);
}

std::optional<std::vector<std::optional<io::Pose2D>>> groundTruthAtScans(const std::string &path,
                                                                         const io::ScanLog &log, std::string &why) {
  const io::Trajectory truth = io::readTum(path);
  if (const std::size_t repeated = evaluation::nonIncreasingStamps(truth); repeated > 0) {
    why = path + ": " + stampsDoNotIncrease(repeated, truth.size(), "");
    return std::nullopt;
  }
  std::vector<std::optional<io::Pose2D>> poses;
  poses.reserve(log.entries.size());
  for (const io::LogEntry &entry : log.entries) poses.push_back(evaluation::poseAt(truth, entry.scan.stamp));
  return poses;
}

void warnOfMissingOdometry(const io::ScanLog &log, const std::string &guess, const io::LogReadOptions &read) {
  if (guess != "odom") return;
  std::size_t without = 0;
  for (const io::LogEntry &entry : log.entries) without += entry.odometry ? 0 : 1;
  if (without == 0) return;
  const std::string why = read.wheel_odometry ? "" : " (read with --no-wheel-odometry)";
  if (without == log.entries.size())
    std::fprintf(stderr,
                 "warning: --guess odom, but %s has no wheel odometry%s: every registration starts from no motion\n",
                 log.source.c_str(), why.c_str());
  else
    std::fprintf(stderr,
                 "warning: --guess odom, but %zu of %zu scans of %s have no wheel odometry: their registrations start "
                 "from no motion\n",
                 without, log.entries.size(), log.source.c_str());
}

CLI::Validator inRange(double low, double high, bool open_low) {
  auto text = [](double v) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%g", v);
    return std::string(buffer);
  };
  const std::string range = std::isinf(high) ? (open_low ? "> " : ">= ") + text(low)
                                             : (open_low ? "(" : "[") + text(low) + ", " + text(high) + "]";
  return CLI::Validator(
      [=](std::string &value) -> std::string {
        double v = 0.0;
        try {
          std::size_t used = 0;
          v = std::stod(value, &used);
          if (used != value.size()) throw std::invalid_argument(value);
        } catch (const std::exception &) {
          return "'" + value + "' is not a number";
        }
        if (!(open_low ? v > low : v >= low) || !(v <= high)) return value + " is out of range: must be " + range;
        return {};
      },
      range);
}

void validateMethodOptions(const MethodOptions &options) {
  const odometry::MatcherSettings settings = options.settings();
  std::string why;
  if (!settings.contour.validate(&why) || !settings.registration.validate(&why))
    throw CLI::ValidationError("contour settings", why);
}

void checkOutputFile(const std::string &option, const std::string &path) {
  namespace fs = std::filesystem;
  std::error_code error;
  if (fs::is_directory(path, error)) throw CLI::ValidationError(option, path + ": is a folder, not a file");
  const fs::path folder = fs::path(path).parent_path();
  if (!folder.empty() && !fs::is_directory(folder, error))
    throw CLI::ValidationError(option, path + ": folder " + folder.string() + " does not exist");
}

void prepareOutputFolder(const std::string &option, const std::string &path) {
  namespace fs = std::filesystem;
  std::error_code error;
  if (fs::exists(path, error) && !fs::is_directory(path, error))
    throw CLI::ValidationError(option, path + ": exists and is not a folder");
  fs::create_directories(path, error);
  if (!fs::is_directory(path, error))
    throw CLI::ValidationError(option, path + ": cannot create the folder (" + error.message() + ")");
}

}  // namespace contour_reg::cli

#include <unistd.h>

namespace contour_reg::cli {

ProgressBar::ProgressBar(std::string label) : label_(std::move(label)), enabled_(isatty(STDERR_FILENO) != 0) {}

ProgressBar::~ProgressBar() { finish(); }

void ProgressBar::finish() {
  if (enabled_ && shown_ >= 0) std::fprintf(stderr, "\n");
  shown_ = -1;
}

void ProgressBar::operator()(std::size_t done, std::size_t total) {
  if (!enabled_ || total == 0) return;
  const int percent = static_cast<int>(100 * done / total);
  if (percent == shown_) return;
  shown_ = percent;
  const int width = 30, filled = percent * width / 100;
  std::fprintf(stderr, "\r%s [%s%s] %3d%%", label_.c_str(), std::string(std::size_t(filled), '#').c_str(),
               std::string(std::size_t(width - filled), ' ').c_str(), percent);
  std::fflush(stderr);
}

}  // namespace contour_reg::cli
