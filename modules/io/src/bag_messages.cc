#include "bag_messages.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "log_assembly.h"

namespace contour_reg::io::detail {

namespace {

// The frame wheel odometry is given in (REP 105): its children's poses in it are odometry.
constexpr char kOdometryFrame[] = "odom";

// Why the message's beam timing cannot be used (empty when it can): beams are taken in
// index order, time_increment apart, and the sweep fits in the scan period (scan_time).
std::string beamTimingProblem(const ScanMessage &message) {
  const double increment = message.time_increment, period = message.scan_time;
  if (!std::isfinite(increment) || increment < 0.0)
    return "time_increment " + std::to_string(increment) + " s is not a beam interval >= 0";
  const double sweep = increment * static_cast<double>(message.ranges.size() - 1);
  if (std::isfinite(period) && period > 0.0 && sweep > 1.01 * period)
    return "the sweep (" + std::to_string(sweep) + " s) is longer than scan_time (" + std::to_string(period) + " s)";
  return {};
}

}  // namespace

bool addScan(const ScanMessage &message, double max_range, std::size_t max_beams, const std::string &where,
             std::size_t index, ScanLog &log) {
  if (message.ranges.size() < 2 || message.ranges.size() > max_beams) {
    log.report.add(where, index, "bad beam count " + std::to_string(message.ranges.size()));
    return false;
  }
  if (!std::isfinite(message.angle_min) || !std::isfinite(message.angle_increment) || message.angle_increment == 0.0f) {
    log.report.add(where, index, "bad beam geometry");
    return false;
  }
  if (!std::isfinite(message.stamp)) {
    log.report.add(where, index, "timestamp is not a finite number");
    return false;
  }
  LogEntry &entry = log.entries.emplace_back();
  LaserScan &scan = entry.scan;
  scan.stamp = message.stamp;
  scan.angle_min = message.angle_min;
  scan.angle_increment = message.angle_increment;
  scan.range_min = std::max(0.0f, message.range_min);
  scan.range_max = message.range_max > 0.0f ? std::min<double>(message.range_max, max_range) : max_range;
  scan.ranges.resize(message.ranges.size());
  for (std::size_t n = 0; n < message.ranges.size(); ++n)
    scan.ranges[n] = scan.isValidRange(message.ranges[n]) ? message.ranges[n] : std::numeric_limits<float>::quiet_NaN();
  const std::string timing = beamTimingProblem(message);
  if (timing.empty())
    scan.time_increment = message.time_increment;
  else
    log.report.add(where, index, timing + ": the scan is read without beam timing");
  return true;
}

ScanMessage scanMessageOf(const LaserScan &scan) {
  ScanMessage message;
  message.stamp = scan.stamp;
  message.frame_id = "laser";
  message.angle_min = static_cast<float>(scan.angle_min);
  message.angle_increment = static_cast<float>(scan.angle_increment);
  message.angle_max = static_cast<float>(scan.bearing(scan.ranges.empty() ? 0 : scan.ranges.size() - 1));
  message.time_increment = static_cast<float>(scan.time_increment);
  // A spinning LIDAR's period: one turn of beams (0 without timing).
  const bool timed = scan.time_increment > 0.0 && scan.angle_increment != 0.0;
  message.scan_time = timed ? static_cast<float>(scan.time_increment / beamInterval(1.0, scan.angle_increment)) : 0.0f;
  message.range_min = static_cast<float>(scan.range_min);
  float farthest = 0.0f;
  message.ranges.resize(scan.ranges.size());
  for (std::size_t n = 0; n < scan.ranges.size(); ++n) {
    const bool valid = scan.isValidRange(scan.ranges[n]);
    message.ranges[n] = valid ? scan.ranges[n] : std::numeric_limits<float>::infinity();
    if (valid) farthest = std::max(farthest, scan.ranges[n]);
  }
  message.range_max = scan.range_max > 0.0 ? static_cast<float>(scan.range_max) : std::nextafter(farthest, 1e9f);
  return message;
}

float firstEcho(const std::vector<float> &echoes) {
  return echoes.empty() ? std::numeric_limits<float>::quiet_NaN() : echoes.front();
}

std::string frameName(std::string name) { return name.empty() || name[0] != '/' ? name : name.substr(1); }

double yawOfQuaternion(double x, double y, double z, double w) {
  return std::atan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z));
}

void TransformTree::add(const std::string &parent, const std::string &child, const Pose2D &child_in_parent,
                        double stamp) {
  if (!std::isfinite(child_in_parent.x + child_in_parent.y + child_in_parent.yaw)) return;
  parent_of_.emplace(frameName(child), std::make_pair(frameName(parent), child_in_parent));
  if (frameName(parent) == kOdometryFrame && std::isfinite(stamp))
    odometry_of_[frameName(child)].push_back({stamp, child_in_parent});
}

std::optional<std::pair<std::string, std::vector<StampedPose>>> TransformTree::odometryOf(
    const std::string &scan_frame) const {
  for (const auto &[robot, poses] : odometry_of_)
    if (poseIn(robot, frameName(scan_frame))) return std::make_pair(robot, poses);
  if (odometry_of_.size() == 1) return *odometry_of_.begin();
  return std::nullopt;
}

std::optional<Pose2D> TransformTree::poseIn(const std::string &base, std::string frame) const {
  Pose2D pose{};
  for (std::size_t depth = 0; depth < 32; ++depth) {
    if (frame == base) return pose;
    const auto up = parent_of_.find(frame);
    if (up == parent_of_.end()) return std::nullopt;
    pose = compose(up->second.second, pose);
    frame = up->second.first;
  }
  return std::nullopt;
}

void finishBagLog(const std::string &path, const TransformTree &tree, const std::string &scan_frame,
                  const std::string &base_frame, std::vector<StampedPose> odometry, ScanLog &log) {
  if (log.entries.empty())
    throw ReadError(path + ": no usable scan in " + std::to_string(log.report.lines) + " messages" +
                    (log.report.problems.empty() ? "" : " (first problem: " + log.report.problems.front() + ")"));
  std::string base = base_frame.empty() ? "base_link" : base_frame;
  if (odometry.empty()) {
    if (auto from_tf = tree.odometryOf(scan_frame)) {
      base = from_tf->first;
      odometry = std::move(from_tf->second);
    }
  }
  if (!scan_frame.empty()) log.laser_pose = tree.poseIn(base, scan_frame);
  finishLog(log, std::move(odometry));
}

}  // namespace contour_reg::io::detail
