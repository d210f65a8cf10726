#include "contour_reg/io/read_log.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include "contour_reg/io/carmen.h"
#include "contour_reg/io/pcd_folder.h"
#include "contour_reg/io/rosbag.h"
#include "contour_reg/io/rosbag2.h"

namespace contour_reg::io {

namespace {

ScanLog readAny(const std::string &path, const LogReadOptions &options) {
  namespace fs = std::filesystem;
  std::error_code error;
  RosbagOptions bag;
  bag.scan_topic = options.scan_topic;
  bag.odometry_topic = options.odometry_topic;
  bag.max_range = options.max_range;
  bag.max_beams = options.max_beams;
  if (isRosbag2(path)) return readRosbag2(path, bag);
  if (fs::is_directory(path, error)) return readPcdFolder(path, options.max_range);
  if (fs::path(path).extension() == ".bag") return readRosbag(path, bag);
  CarmenOptions carmen;
  carmen.max_range = options.max_range;
  carmen.max_beams = options.max_beams;
  return readCarmen(path, carmen);
}

// `scan` with every `step`-th beam, from the first.
void keepEveryBeam(std::size_t step, LaserScan &scan) {
  std::size_t kept = 0;
  for (std::size_t n = 0; n < scan.ranges.size(); n += step) scan.ranges[kept++] = scan.ranges[n];
  scan.ranges.resize(kept);
  scan.angle_increment *= static_cast<double>(step);
  scan.time_increment *= static_cast<double>(step);
}

}  // namespace

ScanLog readLog(const std::string &path, const LogReadOptions &options) {
  if (options.beam_step == 0) throw std::invalid_argument("beam_step must be >= 1");
  if (!(options.max_range > 0.0)) throw std::invalid_argument("max_range must be > 0 m");
  if (!(options.scan_period >= 0.0 && options.scan_period <= LogReadOptions::kLongestScanPeriod))
    throw std::invalid_argument("scan_period must be within 0-10 s");
  if (options.laser_pose && !isMounting(*options.laser_pose))
    throw std::invalid_argument("laser_pose must be finite, within 100 m of the robot and a turn (2 pi rad)");
  ScanLog log = readAny(path, options);
  if (options.beam_step > 1)
    for (LogEntry &entry : log.entries) keepEveryBeam(options.beam_step, entry.scan);
  if (options.scan_period > 0.0)
    for (LogEntry &entry : log.entries)
      if (entry.scan.time_increment == 0.0)
        entry.scan.time_increment = beamInterval(options.scan_period, entry.scan.angle_increment);
  if (options.laser_pose) log.laser_pose = options.laser_pose;
  if (const std::optional<Pose2D> &mounting = log.laser_pose; mounting && !isMounting(*mounting)) {
    char message[200];
    std::snprintf(message, sizeof message,
                  ": the log mounts the laser %.3g m from the robot, turned %.3g rad: no robot carries it so (at "
                  "most %.0f m); give its mounting instead (--laser-pose X Y YAW, laser_pose= in Python)",
                  std::hypot(mounting->x, mounting->y), mounting->yaw, kFarthestMounting);
    throw ReadError(path + message);
  }
  if (!options.wheel_odometry) leaveOutWheelOdometry(log);
  return log;
}

void writeLog(const std::string &path, const ScanLog &log) {
  const std::filesystem::path extension = std::filesystem::path(path).extension();
  if (extension == ".zstd")
    throw ReadError(path + ": compressed storage files are read, not written (an .mcap file's chunks are zstd)");
  if (extension == ".bag")
    writeRosbag(path, log);
  else if (extension == ".db3" || extension == ".mcap")
    writeRosbag2(path, log);
  else
    writeCarmen(path, log);
}

void leaveOutWheelOdometry(ScanLog &log) {
  log.wheel_odometry.clear();
  for (LogEntry &entry : log.entries) entry.odometry.reset();
}

std::size_t nearestEntry(const ScanLog &log, double stamp) {
  const auto it = std::lower_bound(log.entries.begin(), log.entries.end(), stamp,
                                   [](const LogEntry &e, double t) { return e.scan.stamp < t; });
  std::size_t k = static_cast<std::size_t>(it - log.entries.begin());
  if (k == log.entries.size() || (k > 0 && stamp - log.entries[k - 1].scan.stamp < it->scan.stamp - stamp)) --k;
  return k;
}

}  // namespace contour_reg::io
