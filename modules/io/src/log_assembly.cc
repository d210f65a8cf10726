#include "log_assembly.h"

#include <algorithm>
#include <cmath>

namespace contour_reg::io::detail {

std::optional<Pose2D> interpolatePose(const std::vector<StampedPose> &samples, double stamp) {
  if (samples.empty() || stamp < samples.front().stamp || stamp > samples.back().stamp) return std::nullopt;
  auto after = std::lower_bound(samples.begin(), samples.end(), stamp,
                                [](const StampedPose &p, double t) { return p.stamp < t; });
  if (after == samples.begin()) return after->pose;
  const StampedPose &b = *after, &a = *(after - 1);
  const double w = b.stamp > a.stamp ? (stamp - a.stamp) / (b.stamp - a.stamp) : 0.0;
  const double turn = std::remainder(b.pose.yaw - a.pose.yaw, 2.0 * M_PI);
  return Pose2D{a.pose.x + w * (b.pose.x - a.pose.x), a.pose.y + w * (b.pose.y - a.pose.y), a.pose.yaw + w * turn};
}

void finishLog(ScanLog &log, std::vector<StampedPose> odometry) {
  for (std::size_t k = 1; k < log.entries.size(); ++k)
    if (log.entries[k].scan.stamp < log.entries[k - 1].scan.stamp) ++log.report.reordered;
  std::stable_sort(log.entries.begin(), log.entries.end(),
                   [](const LogEntry &a, const LogEntry &b) { return a.scan.stamp < b.scan.stamp; });
  std::stable_sort(odometry.begin(), odometry.end(),
                   [](const StampedPose &a, const StampedPose &b) { return a.stamp < b.stamp; });
  for (LogEntry &entry : log.entries)
    if (!entry.odometry) entry.odometry = interpolatePose(odometry, entry.scan.stamp);
  log.wheel_odometry = std::move(odometry);
}

std::vector<StampedPose> odometryToWrite(const ScanLog &log) {
  if (!log.wheel_odometry.empty()) return log.wheel_odometry;
  std::vector<StampedPose> own;
  for (const LogEntry &entry : log.entries)
    if (entry.odometry) own.push_back({entry.scan.stamp, *entry.odometry});
  return own;
}

}  // namespace contour_reg::io::detail
