#include "contour_reg/io/carmen.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "contour_reg/io/pose2d.h"
#include "log_assembly.h"
#include "text_lines.h"

namespace contour_reg::io {

namespace {

using detail::parseNumber;
using Fields = std::vector<std::string_view>;

// Reads fields [first, first + count) as numbers; false when any is missing or not a number.
bool numbers(const Fields &fields, std::size_t first, std::size_t count, std::vector<double> &out) {
  if (first + count > fields.size()) return false;
  out.resize(count);
  for (std::size_t k = 0; k < count; ++k)
    if (!parseNumber(fields[first + k], out[k])) return false;
  return true;
}

bool number(const Fields &fields, std::size_t index, double &value) {
  return index < fields.size() && parseNumber(fields[index], value);
}

std::optional<Pose2D> poseAt(const Fields &fields, std::size_t index) {
  std::vector<double> v;
  if (!numbers(fields, index, 3, v) || !std::isfinite(v[0] + v[1] + v[2])) return std::nullopt;
  return Pose2D{v[0], v[1], v[2]};
}

// Ranges at or above max_range, and anything not finite, become NaN.
void fillRanges(LaserScan &scan, const std::vector<double> &values, double max_range) {
  scan.ranges.resize(values.size());
  for (std::size_t n = 0; n < values.size(); ++n) {
    const double r = values[n];
    scan.ranges[n] = (std::isfinite(r) && r > 0.0 && r < max_range) ? static_cast<float>(r)
                                                                    : std::numeric_limits<float>::quiet_NaN();
  }
}

// Parses one line into `entry` (laser lines) or `odometry` (ODOM lines).
// Returns an empty string on success, a description of the problem otherwise;
// `is_laser` / `is_odometry` tell what the line was.
// ROBOTLASER1 lines also give the laser's pose on the robot (`laser_pose`).
std::string parseLine(const Fields &f, const CarmenOptions &options, LogEntry &entry, StampedPose &odometry,
                      std::optional<Pose2D> &laser_pose, bool &is_laser, bool &is_odometry) {
  is_laser = is_odometry = false;
  const std::string_view type = f[0];
  std::vector<double> values;
  double count_value = 0.0;
  auto beam_count = [&](std::size_t index, std::size_t &n) -> std::string {
    if (!number(f, index, count_value) || count_value < 0.0 || count_value != std::floor(count_value))
      return "bad beam count";
    if (count_value > static_cast<double>(options.max_beams)) return "absurd beam count";
    n = static_cast<std::size_t>(count_value);
    return {};
  };

  if (type == "FLASER" || type == "RLASER") {
    std::size_t n = 0;
    if (auto e = beam_count(1, n); !e.empty()) return e;
    if (n < 2) return "fewer than 2 beams";
    if (!numbers(f, 2, n, values)) return "truncated or non-numeric ranges";
    LaserScan &scan = entry.scan;
    scan.angle_min = -M_PI / 2;
    scan.angle_increment = M_PI / static_cast<double>(n - n % 2);
    scan.range_max = options.max_range;
    fillRanges(scan, values, options.max_range);
    entry.odometry = poseAt(f, 2 + n + 3);
    if (!number(f, 2 + n + 6, scan.stamp)) return "missing timestamp";
    is_laser = true;
  } else if (type == "ROBOTLASER1" || type.rfind("RAWLASER", 0) == 0) {
    std::vector<double> head;
    if (!numbers(f, 2, 5, head)) return "truncated beam geometry";  // start, fov, resolution, max, accuracy
    std::size_t n = 0;
    if (auto e = beam_count(8, n); !e.empty()) return e;
    if (n < 2) return "fewer than 2 beams";
    if (!numbers(f, 9, n, values)) return "truncated or non-numeric ranges";
    double remissions_value = 0.0;
    if (!number(f, 9 + n, remissions_value) || !std::isfinite(remissions_value) || remissions_value < 0.0 ||
        remissions_value > static_cast<double>(options.max_beams))
      return "bad remission count";
    std::size_t next = 10 + n + static_cast<std::size_t>(remissions_value);
    LaserScan &scan = entry.scan;
    scan.angle_min = head[0];
    scan.angle_increment = head[2];
    if (!std::isfinite(scan.angle_min) || !std::isfinite(scan.angle_increment) || scan.angle_increment == 0.0)
      return "bad beam geometry";
    const double max_range =
        (head[3] > 0.0 && std::isfinite(head[3])) ? std::min(head[3], options.max_range) : options.max_range;
    scan.range_max = max_range;
    fillRanges(scan, values, max_range);
    if (type == "ROBOTLASER1") {
      const auto laser = poseAt(f, next);
      entry.odometry = poseAt(f, next + 3);  // laser pose, then robot pose
      if (laser && entry.odometry) laser_pose = between(*entry.odometry, *laser);
      next += 6 + 5;  // poses, tv rv forward_safety side_safety turn_axis
    }
    if (!number(f, next, scan.stamp)) return "missing timestamp";
    is_laser = true;
  } else if (type == "ODOM") {
    auto pose = poseAt(f, 1);
    if (!pose) return "bad pose";
    if (!number(f, 7, odometry.stamp)) return "missing timestamp";
    odometry.pose = *pose;
    is_odometry = true;
  }
  if ((is_laser && !std::isfinite(entry.scan.stamp)) || (is_odometry && !std::isfinite(odometry.stamp)))
    return "timestamp is not a finite number";
  return {};
}

}  // namespace

void ReadReport::add(const std::string &where, std::size_t line, const std::string &what, Shown shown) {
  ++skipped;
  if (problems.size() < kFirstProblems || shown == kAlwaysShown)
    problems.push_back(where + ":" + std::to_string(line) + ": " + what);
}

ScanLog readCarmen(const std::string &path, const CarmenOptions &options) {
  detail::LineReader reader(path);
  if (!reader.isOpen()) throw ReadError(path + ": cannot open");
  ScanLog log;
  log.source = path;
  std::vector<StampedPose> odometry;
  std::string line;
  while (reader.next(line)) {
    ++log.report.lines;
    const Fields fields = detail::splitFields(line);
    if (fields.empty() || fields[0][0] == '#') continue;
    LogEntry entry;
    StampedPose odom{};
    std::optional<Pose2D> laser_pose;
    bool is_laser = false, is_odometry = false;
    std::string problem = parseLine(fields, options, entry, odom, laser_pose, is_laser, is_odometry);
    if (problem.empty() && is_laser && reader.lastLineUnterminated()) problem = "truncated last line";
    if (!problem.empty()) {
      log.report.add(path, reader.lineNumber(), std::string(fields[0].substr(0, 24)) + ": " + problem);
      continue;
    }
    if (is_laser) log.entries.push_back(std::move(entry));
    if (is_odometry) odometry.push_back(odom);
    if (laser_pose && !log.laser_pose) log.laser_pose = laser_pose;
  }
  // Named past the first problems too: all that follows is lost.
  if (!reader.error().empty())
    log.report.add(path, reader.lineNumber() + 1, reader.error() + ": the rest is not read", ReadReport::kAlwaysShown);
  if (log.entries.empty())
    throw ReadError(path + ": no usable scan in " + std::to_string(log.report.lines) + " lines" +
                    (log.report.problems.empty() ? "" : " (first problem: " + log.report.problems.front() + ")"));

  detail::finishLog(log, std::move(odometry));
  return log;
}

void writeCarmen(const std::string &path, const ScanLog &log) {
  std::FILE *file = std::fopen(path.c_str(), "w");
  if (!file) throw ReadError(path + ": cannot write");
  std::fprintf(file, "# CARMEN log written by contour_reg\n");
  std::fprintf(file,
               "# ROBOTLASER1 laser_type start_angle field_of_view angular_resolution maximum_range accuracy "
               "remission_mode num_readings [ranges] num_remissions laser_pose robot_pose tv rv "
               "forward_safety_dist side_safety_dist turn_axis timestamp host logger_timestamp\n");
  auto writeOdometry = [&](const StampedPose &sample) {
    std::fprintf(file, "ODOM %.6f %.6f %.6f 0 0 0 %.6f sim %.6f\n", sample.pose.x, sample.pose.y, sample.pose.yaw,
                 sample.stamp, sample.stamp);
  };
  const std::vector<StampedPose> odometry = detail::odometryToWrite(log);
  std::size_t next_odometry = 0;
  for (const LogEntry &entry : log.entries) {
    const LaserScan &s = entry.scan;
    const Pose2D pose = entry.odometry.value_or(Pose2D{});
    const Pose2D laser = compose(pose, log.laser_pose.value_or(Pose2D{}));
    const double max_range = s.range_max > 0.0 ? s.range_max : 80.0;
    for (; next_odometry < odometry.size() && odometry[next_odometry].stamp <= s.stamp; ++next_odometry)
      writeOdometry(odometry[next_odometry]);  // the odometry up to this scan
    std::fprintf(file, "ROBOTLASER1 0 %.9f %.9f %.9f %.3f 0.01 0 %zu", s.angle_min,
                 s.angle_increment * static_cast<double>(s.ranges.size() > 0 ? s.ranges.size() - 1 : 0),
                 s.angle_increment, max_range, s.ranges.size());
    for (float r : s.ranges) std::fprintf(file, " %.4f", std::isfinite(r) ? static_cast<double>(r) : max_range);
    std::fprintf(file, " 0 %.6f %.6f %.6f %.6f %.6f %.6f 0 0 0 0 0 %.6f sim %.6f\n", laser.x, laser.y, laser.yaw,
                 pose.x, pose.y, pose.yaw, s.stamp, s.stamp);
  }
  for (; next_odometry < odometry.size(); ++next_odometry) writeOdometry(odometry[next_odometry]);
  const bool ok = std::fflush(file) == 0;
  std::fclose(file);
  if (!ok) throw ReadError(path + ": write failed");
}

}  // namespace contour_reg::io
