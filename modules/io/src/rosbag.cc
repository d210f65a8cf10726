#include "contour_reg/io/rosbag.h"

#include <cmath>
#include <limits>

#include "log_assembly.h"

#ifdef CONTOUR_REG_HAVE_ROSBAG
#include <nav_msgs/Odometry.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <sensor_msgs/LaserScan.h>
#endif

namespace contour_reg::io {

#ifdef CONTOUR_REG_HAVE_ROSBAG

namespace {

std::string firstTopicOfType(const rosbag::Bag &bag, const std::string &type) {
  rosbag::View all(bag);
  for (const rosbag::ConnectionInfo *connection : all.getConnections())
    if (connection->datatype == type) return connection->topic;
  return {};
}

double yawOf(const geometry_msgs::Quaternion &q) {
  return std::atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z));
}

LogEntry toEntry(const sensor_msgs::LaserScan &message, double max_range) {
  LogEntry entry;
  LaserScan &scan = entry.scan;
  scan.stamp = message.header.stamp.toSec();
  scan.angle_min = message.angle_min;
  scan.angle_increment = message.angle_increment;
  scan.range_min = std::max(0.0f, message.range_min);
  scan.range_max = message.range_max > 0.0f ? std::min<double>(message.range_max, max_range) : max_range;
  scan.ranges.resize(message.ranges.size());
  for (std::size_t n = 0; n < message.ranges.size(); ++n)
    scan.ranges[n] = scan.isValidRange(message.ranges[n]) ? message.ranges[n] : std::numeric_limits<float>::quiet_NaN();
  return entry;
}

}  // namespace

bool rosbagSupported() { return true; }

ScanLog readRosbag(const std::string &path, const RosbagOptions &options) {
  ScanLog log;
  log.source = path;
  std::vector<detail::TimedPose> odometry;
  try {
    rosbag::Bag bag(path, rosbag::bagmode::Read);
    const std::string scan_topic =
        options.scan_topic.empty() ? firstTopicOfType(bag, "sensor_msgs/LaserScan") : options.scan_topic;
    const std::string odometry_topic =
        options.odometry_topic.empty() ? firstTopicOfType(bag, "nav_msgs/Odometry") : options.odometry_topic;
    if (scan_topic.empty()) throw ReadError(path + ": no sensor_msgs/LaserScan topic in the bag");
    std::vector<std::string> topics{scan_topic};
    if (!odometry_topic.empty()) topics.push_back(odometry_topic);
    rosbag::View view(bag, rosbag::TopicQuery(topics));
    std::size_t index = 0;
    for (const rosbag::MessageInstance &message : view) {
      ++index;
      ++log.report.lines;
      const std::string where = path + " (" + message.getTopic() + ")";
      try {
        if (message.getTopic() == scan_topic) {
          auto scan = message.instantiate<sensor_msgs::LaserScan>();
          if (!scan) {
            log.report.add(where, index, "not a sensor_msgs/LaserScan");
          } else if (scan->ranges.size() < 2 || scan->ranges.size() > options.max_beams) {
            log.report.add(where, index, "bad beam count " + std::to_string(scan->ranges.size()));
          } else if (!std::isfinite(scan->angle_min) || !std::isfinite(scan->angle_increment) ||
                     scan->angle_increment == 0.0f) {
            log.report.add(where, index, "bad beam geometry");
          } else {
            log.entries.push_back(toEntry(*scan, options.max_range));
          }
        } else if (auto odom = message.instantiate<nav_msgs::Odometry>()) {
          const auto &pose = odom->pose.pose;
          const Pose2D p{pose.position.x, pose.position.y, yawOf(pose.orientation)};
          if (std::isfinite(p.x + p.y + p.yaw))
            odometry.push_back({odom->header.stamp.toSec(), p});
          else
            log.report.add(where, index, "odometry pose is not finite");
        }
      } catch (const std::exception &error) {
        log.report.add(where, index, std::string("cannot decode message: ") + error.what());
      }
    }
  } catch (const ReadError &) {
    throw;
  } catch (const std::exception &error) {
    throw ReadError(path + ": not a readable ROS 1 bag: " + error.what());
  }
  if (log.entries.empty())
    throw ReadError(path + ": no usable scan in " + std::to_string(log.report.lines) + " messages" +
                    (log.report.problems.empty() ? "" : " (first problem: " + log.report.problems.front() + ")"));
  detail::finishLog(log, std::move(odometry));
  return log;
}

#else

bool rosbagSupported() { return false; }

ScanLog readRosbag(const std::string &path, const RosbagOptions &) {
  throw ReadError(path +
                  ": this build of contour_reg cannot read ROS bags (install librosbag-storage-dev, "
                  "libsensor-msgs-dev and libnav-msgs-dev, then rebuild)");
}

#endif

}  // namespace contour_reg::io
