#include "contour_reg/io/rosbag.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>
#include <stdexcept>
#include <type_traits>
#include <utility>
#include <vector>

#include "bag_messages.h"
#include "log_assembly.h"
#include "rosbag_check.h"

#ifdef CONTOUR_REG_HAVE_ROSBAG
#include <nav_msgs/Odometry.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <sensor_msgs/LaserScan.h>
#include <sensor_msgs/MultiEchoLaserScan.h>
#include <tf2_msgs/TFMessage.h>
#include <boost/make_shared.hpp>
#endif

#include <map>

#include "contour_reg/io/pose2d.h"

namespace contour_reg::io {

#ifdef CONTOUR_REG_HAVE_ROSBAG

namespace {

const std::string kLaserScanType = "sensor_msgs/LaserScan";
const std::string kMultiEchoScanType = "sensor_msgs/MultiEchoLaserScan";

std::vector<std::string> topicsOfType(const rosbag::Bag &bag, const std::string &type) {
  std::vector<std::string> topics;
  rosbag::View all(bag);
  for (const rosbag::ConnectionInfo *connection : all.getConnections())
    if (connection->datatype == type && std::find(topics.begin(), topics.end(), connection->topic) == topics.end())
      topics.push_back(connection->topic);
  return topics;
}

// The topic the options name, or the bag's first of the first of `types` it carries when they
// name none, with its type. A named topic the bag does not carry with one of those types is an
// error, so that a mistyped name is not read as a bag without those messages.
std::pair<std::string, std::string> topicToRead(const rosbag::Bag &bag, const std::string &path,
                                                const std::string &named, const std::vector<std::string> &types) {
  std::string carried, wanted;
  for (const std::string &type : types) {
    const std::vector<std::string> topics = topicsOfType(bag, type);
    if (named.empty() && !topics.empty()) return {topics.front(), type};
    if (!named.empty() && std::find(topics.begin(), topics.end(), named) != topics.end()) return {named, type};
    for (const std::string &topic : topics) carried += (carried.empty() ? "" : ", ") + topic;
    wanted += (wanted.empty() ? "" : " or ") + type;
  }
  if (named.empty()) return {};
  throw ReadError(path + ": no " + wanted + " topic " + named + " in the bag (" +
                  (carried.empty() ? "it has none" : "it has " + carried) + ")");
}

geometry_msgs::Quaternion quaternionOf(double yaw) {
  geometry_msgs::Quaternion q;
  q.z = std::sin(0.5 * yaw);
  q.w = std::cos(0.5 * yaw);
  return q;
}

double yawOf(const geometry_msgs::Quaternion &q) { return detail::yawOfQuaternion(q.x, q.y, q.z, q.w); }

// The message's fields, its ranges moved: a sensor_msgs/LaserScan, or a MultiEchoLaserScan
// with each beam's first echo as its range.
template <typename Message>
detail::ScanMessage scanMessage(Message &message) {
  detail::ScanMessage scan;
  scan.stamp = message.header.stamp.toSec();
  scan.frame_id = message.header.frame_id;
  scan.angle_min = message.angle_min;
  scan.angle_max = message.angle_max;
  scan.angle_increment = message.angle_increment;
  scan.time_increment = message.time_increment;
  scan.scan_time = message.scan_time;
  scan.range_min = message.range_min;
  scan.range_max = message.range_max;
  if constexpr (std::is_same_v<Message, sensor_msgs::LaserScan>) {
    scan.ranges = std::move(message.ranges);
  } else {
    scan.ranges.reserve(message.ranges.size());
    for (const sensor_msgs::LaserEcho &beam : message.ranges) scan.ranges.push_back(detail::firstEcho(beam.echoes));
  }
  return scan;
}

// ROS's deserialization sizes an array from the length the message declares before it checks
// that the message holds that many elements: a corrupt length asks for gigabytes. These read a
// message's bytes first and check the lengths of its arrays against them.

// The 4-byte length at `at` of `bytes`, and `at` moved past it; false past the end.
bool lengthAt(const std::vector<std::uint8_t> &bytes, std::size_t &at, std::uint64_t &length) {
  if (bytes.size() < 4 || at > bytes.size() - 4) return false;
  std::uint32_t value = 0;
  std::memcpy(&value, bytes.data() + at, 4);
  length = value;
  at += 4;
  return true;
}

// Whether `bytes` (a serialized sensor_msgs/LaserScan) holds the ranges and intensities it declares.
bool laserScanFits(const std::vector<std::uint8_t> &bytes) {
  std::size_t at = 12;  // the header's sequence number and stamp
  std::uint64_t length = 0;
  if (!lengthAt(bytes, at, length) || length > bytes.size() - at) return false;  // frame_id
  at += length + 7 * 4;                      // angles, times and range limits: seven float32
  for (int array = 0; array < 2; ++array) {  // ranges, intensities: float32 each
    if (!lengthAt(bytes, at, length) || 4 * length > bytes.size() - at) return false;
    at += 4 * length;
  }
  return true;
}

// Whether `bytes` (a serialized sensor_msgs/MultiEchoLaserScan) holds the echoes of each beam
// it declares, for the ranges and the intensities.
bool multiEchoScanFits(const std::vector<std::uint8_t> &bytes) {
  std::size_t at = 12;  // the header's sequence number and stamp
  std::uint64_t length = 0;
  if (!lengthAt(bytes, at, length) || length > bytes.size() - at) return false;  // frame_id
  at += length + 7 * 4;                      // angles, times and range limits: seven float32
  for (int array = 0; array < 2; ++array) {  // ranges, intensities: a float32 array per beam
    std::uint64_t beams = 0;
    if (!lengthAt(bytes, at, beams) || 4 * beams > bytes.size() - at) return false;
    for (std::uint64_t beam = 0; beam < beams; ++beam) {
      if (!lengthAt(bytes, at, length) || 4 * length > bytes.size() - at) return false;
      at += 4 * length;
    }
  }
  return true;
}

// Whether `bytes` (a serialized tf2_msgs/TFMessage) can hold the transforms it declares: each
// takes at least 76 bytes (two empty frame names, stamp, sequence number, seven float64).
bool transformsFit(const std::vector<std::uint8_t> &bytes) {
  std::size_t at = 0;
  std::uint64_t count = 0;
  return lengthAt(bytes, at, count) && 76 * count <= bytes.size() - at;
}

// `message` as a T: null when it is of another type; throws when `fits` says its bytes do not
// hold what they declare, or they do not deserialize.
template <typename T>
boost::shared_ptr<T> decoded(const rosbag::MessageInstance &message, bool (*fits)(const std::vector<std::uint8_t> &)) {
  if (message.getMD5Sum() != ros::message_traits::MD5Sum<T>::value() && message.getMD5Sum() != "*") return nullptr;
  std::vector<std::uint8_t> bytes(message.size());
  ros::serialization::OStream out(bytes.data(), static_cast<std::uint32_t>(bytes.size()));
  message.write(out);
  if (!fits(bytes)) throw std::runtime_error("an array longer than the message");
  auto decoded = boost::make_shared<T>();
  ros::serialization::IStream in(bytes.data(), static_cast<std::uint32_t>(bytes.size()));
  ros::serialization::deserialize(in, *decoded);
  return decoded;
}

}  // namespace

bool rosbagSupported() { return true; }

ScanLog readRosbag(const std::string &path, const RosbagOptions &options) {
  ScanLog log;
  log.source = path;
  std::vector<StampedPose> odometry;
  detail::TransformTree tree;
  std::string scan_frame, base_frame;  // of the first scan and the first odometry message
  const detail::BagCheck check = detail::checkBagStructure(path);
  if (!check.fatal.empty()) throw ReadError(path + ": not a readable ROS 1 bag: " + check.fatal);
  try {
    rosbag::Bag bag(path, rosbag::bagmode::Read);
    const auto [scan_topic, scan_type] =
        topicToRead(bag, path, options.scan_topic, {kLaserScanType, kMultiEchoScanType});
    const std::string odometry_topic = topicToRead(bag, path, options.odometry_topic, {"nav_msgs/Odometry"}).first;
    if (scan_topic.empty())
      throw ReadError(path + ": no " + kLaserScanType + " or " + kMultiEchoScanType + " topic in the bag");
    std::vector<std::string> topics{scan_topic};
    if (!odometry_topic.empty()) topics.push_back(odometry_topic);
    const std::vector<std::string> tf_topics = topicsOfType(bag, "tf2_msgs/TFMessage");
    topics.insert(topics.end(), tf_topics.begin(), tf_topics.end());
    rosbag::View view(bag, rosbag::TopicQuery(topics));
    // The connection numbers of each topic, as the bag's index names them.
    std::map<std::string, std::vector<std::uint32_t>> connections;
    for (const rosbag::ConnectionInfo *connection : view.getConnections())
      connections[connection->topic].push_back(connection->id);
    std::size_t index = 0;
    for (const rosbag::MessageInstance &message : view) {
      ++index;
      ++log.report.lines;
      const std::string where = path + " (" + message.getTopic() + ")";
      if (!check.unsafe.empty()) {
        const ros::Time stamp = message.getTime();
        const std::uint64_t key = detail::stampKey(stamp.sec, stamp.nsec);
        const std::vector<std::uint32_t> &ids = connections[message.getTopic()];
        const auto unsafe = std::find_if(ids.begin(), ids.end(), [&](std::uint32_t id) {
          return check.unsafe.count({id, key}) > 0;
        });
        if (unsafe != ids.end()) {
          log.report.add(where, index, "not read: " + check.unsafe.at({*unsafe, key}));
          continue;
        }
      }
      try {
        if (message.getTopic() == scan_topic) {
          std::optional<detail::ScanMessage> read;
          if (scan_type == kLaserScanType) {
            if (auto scan = decoded<sensor_msgs::LaserScan>(message, laserScanFits)) read = scanMessage(*scan);
          } else if (auto scan = decoded<sensor_msgs::MultiEchoLaserScan>(message, multiEchoScanFits)) {
            read = scanMessage(*scan);
          }
          if (!read) {
            log.report.add(where, index, "not a " + scan_type);
          } else {
            const bool first = log.entries.empty();
            if (detail::addScan(*read, options.max_range, options.max_beams, where, index, log) && first)
              scan_frame = detail::frameName(read->frame_id);
          }
        } else if (message.getTopic() != odometry_topic) {
          if (auto transforms = decoded<tf2_msgs::TFMessage>(message, transformsFit))
            for (const geometry_msgs::TransformStamped &t : transforms->transforms)
              tree.add(t.header.frame_id, t.child_frame_id,
                       {t.transform.translation.x, t.transform.translation.y, yawOf(t.transform.rotation)},
                       t.header.stamp.toSec());
        } else if (auto odom = message.instantiate<nav_msgs::Odometry>()) {
          if (base_frame.empty()) base_frame = detail::frameName(odom->child_frame_id);
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
  detail::finishBagLog(path, tree, scan_frame, base_frame, std::move(odometry), log);
  return log;
}

void writeRosbag(const std::string &path, const ScanLog &log) {
  try {
    rosbag::Bag bag(path, rosbag::bagmode::Write);
    std::uint32_t sequence = 0, odometry_sequence = 0;
    const std::vector<StampedPose> samples = detail::odometryToWrite(log);
    std::size_t next_odometry = 0;
    auto writeOdometry = [&](const StampedPose &sample) {
      if (!(sample.stamp >= 0.0) || !std::isfinite(sample.stamp))
        throw ReadError("odometry sample " + std::to_string(odometry_sequence) + " has stamp " +
                        std::to_string(sample.stamp) + " s, which a bag cannot hold");
      const ros::Time stamp(sample.stamp);
      nav_msgs::Odometry odometry;
      odometry.header.seq = odometry_sequence++;
      odometry.header.stamp = stamp;
      odometry.header.frame_id = "odom";
      odometry.child_frame_id = "base_link";
      odometry.pose.pose.position.x = sample.pose.x;
      odometry.pose.pose.position.y = sample.pose.y;
      odometry.pose.pose.orientation = quaternionOf(sample.pose.yaw);
      bag.write("/odom", std::max(stamp, ros::TIME_MIN), odometry);
    };
    for (const LogEntry &entry : log.entries) {
      const LaserScan &scan = entry.scan;
      if (!(scan.stamp >= 0.0) || !std::isfinite(scan.stamp))
        throw ReadError("scan " + std::to_string(sequence) + " has stamp " + std::to_string(scan.stamp) +
                        " s, which a bag cannot hold");
      // A bag's record time must be after its epoch; the header keeps the scan's own stamp.
      const ros::Time stamp(scan.stamp);
      const ros::Time recorded = std::max(stamp, ros::TIME_MIN);
      detail::ScanMessage written = detail::scanMessageOf(scan);
      sensor_msgs::LaserScan message;
      message.header.seq = sequence++;
      message.header.stamp = stamp;
      message.header.frame_id = written.frame_id;
      message.angle_min = written.angle_min;
      message.angle_increment = written.angle_increment;
      message.angle_max = written.angle_max;
      message.time_increment = written.time_increment;
      message.scan_time = written.scan_time;
      message.range_min = written.range_min;
      message.range_max = written.range_max;
      message.ranges = std::move(written.ranges);
      if (sequence == 1 && log.laser_pose) {
        // The mounting, as a robot's static transform publisher gives it, with the first scan.
        geometry_msgs::TransformStamped mounting;
        mounting.header.stamp = recorded;
        mounting.header.frame_id = "base_link";
        mounting.child_frame_id = message.header.frame_id;
        mounting.transform.translation.x = log.laser_pose->x;
        mounting.transform.translation.y = log.laser_pose->y;
        mounting.transform.rotation = quaternionOf(log.laser_pose->yaw);
        tf2_msgs::TFMessage transforms;
        transforms.transforms.push_back(mounting);
        bag.write("/tf_static", recorded, transforms);
      }
      for (; next_odometry < samples.size() && samples[next_odometry].stamp <= scan.stamp; ++next_odometry)
        writeOdometry(samples[next_odometry]);  // the odometry up to this scan
      bag.write("/scan", recorded, message);
    }
    for (; next_odometry < samples.size(); ++next_odometry) writeOdometry(samples[next_odometry]);
    bag.close();
  } catch (const std::exception &error) {
    throw ReadError(path + ": cannot write the bag: " + error.what());
  }
}

#else

bool rosbagSupported() { return false; }

ScanLog readRosbag(const std::string &path, const RosbagOptions &) {
  throw ReadError(path +
                  ": this build of contour_reg cannot read ROS bags (install librosbag-storage-dev, "
                  "libsensor-msgs-dev, libnav-msgs-dev and libtf2-msgs-dev, then rebuild)");
}

void writeRosbag(const std::string &path, const ScanLog &) {
  throw ReadError(path +
                  ": this build of contour_reg cannot write ROS bags (install librosbag-storage-dev, "
                  "libsensor-msgs-dev, libnav-msgs-dev and libtf2-msgs-dev, then rebuild)");
}

#endif

}  // namespace contour_reg::io
