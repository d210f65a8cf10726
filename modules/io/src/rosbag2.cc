#include "contour_reg/io/rosbag2.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <initializer_list>
#include <map>
#include <stdexcept>
#include <vector>

#include "bag_messages.h"
#include "cdr.h"
#include "log_assembly.h"
#include "mcap.h"
#include "sqlite_storage.h"
#include "zstd_storage.h"

namespace contour_reg::io {

namespace {

namespace fs = std::filesystem;

constexpr char kScanType[] = "sensor_msgs/msg/LaserScan";
constexpr char kMultiEchoScanType[] = "sensor_msgs/msg/MultiEchoLaserScan";
constexpr char kOdometryType[] = "nav_msgs/msg/Odometry";
constexpr char kTransformsType[] = "tf2_msgs/msg/TFMessage";
// No message of the types read decompresses to more (a scan of LogReadOptions::max_beams
// ranges and intensities is under 1 MB).
constexpr std::size_t kLargestMessage = std::size_t{64} << 20;

// Whether `file` is a storage file of a ROS 2 bag: sqlite3 (.db3) or MCAP (.mcap), either
// compressed whole by rosbag2 (.zstd after it).
bool isStorageFile(const fs::path &file) {
  const fs::path extension = fs::path(detail::withoutZstd(file.string())).extension();
  return extension == ".db3" || extension == ".mcap";
}

// The storage files of the bag at `path`, in the order they were recorded.
std::vector<std::string> storageFiles(const std::string &path) {
  std::error_code error;
  if (!fs::is_directory(path, error)) return {path};
  const fs::path folder(path), metadata = folder / "metadata.yaml";
  std::vector<std::string> files;
  if (fs::exists(metadata, error)) {
    try {
      const YAML::Node information = YAML::LoadFile(metadata.string())["rosbag2_bagfile_information"];
      if (!information) throw ReadError(metadata.string() + ": no rosbag2_bagfile_information");
      const std::string storage = information["storage_identifier"].as<std::string>("sqlite3");
      if (storage != "sqlite3" && storage != "mcap")
        throw ReadError(path + ": a ROS 2 bag in " + storage + " storage; sqlite3 and mcap are read");
      // Compressed by file or by message (compression_mode); each kind is told by its bytes.
      const std::string compression = information["compression_format"].as<std::string>("");
      if (!compression.empty() && compression != "zstd")
        throw ReadError(path + ": a ROS 2 bag compressed with " + compression + "; zstd and uncompressed are read");
      for (const YAML::Node &file : information["relative_file_paths"])
        files.push_back((folder / file.as<std::string>()).string());
    } catch (const YAML::Exception &e) {
      const std::string line = e.mark.line >= 0 ? ":" + std::to_string(e.mark.line + 1) : "";
      throw ReadError(metadata.string() + line + ": " + e.msg);
    }
  } else {
    for (const fs::directory_entry &entry : fs::directory_iterator(folder, error))
      if (isStorageFile(entry.path())) files.push_back(entry.path().string());
    std::sort(files.begin(), files.end());
  }
  if (files.empty()) throw ReadError(path + ": a ROS 2 bag folder without a storage file");
  return files;
}

double stampOf(detail::CdrReader &in) {
  const auto seconds = in.read<std::int32_t>();
  const auto nanoseconds = in.read<std::uint32_t>();
  return seconds + 1e-9 * nanoseconds;
}

// A LaserScan or MultiEchoLaserScan up to its ranges.
detail::ScanMessage decodeScanFields(detail::CdrReader &in) {
  detail::ScanMessage scan;
  scan.stamp = stampOf(in);
  scan.frame_id = in.readString();
  scan.angle_min = in.read<float>();
  scan.angle_max = in.read<float>();
  scan.angle_increment = in.read<float>();
  scan.time_increment = in.read<float>();
  scan.scan_time = in.read<float>();
  scan.range_min = in.read<float>();
  scan.range_max = in.read<float>();
  return scan;
}

// A sensor_msgs/msg/LaserScan, or a MultiEchoLaserScan with each beam's first echo as its range
// (no return where a beam has none).
detail::ScanMessage decodeScan(detail::CdrReader &in, const std::string &type) {
  detail::ScanMessage scan = decodeScanFields(in);
  if (type != kMultiEchoScanType) {
    scan.ranges = in.readSequence<float>();
    return scan;
  }
  scan.ranges.resize(in.readCount(4));  // each beam's echoes: a count and its float32s
  for (float &range : scan.ranges) range = detail::firstEcho(in.readSequence<float>());
  return scan;
}

// geometry_msgs/msg/Point or Vector3, then Quaternion: the planar pose.
Pose2D planarPose(detail::CdrReader &in) {
  const double x = in.read<double>(), y = in.read<double>();
  in.read<double>();  // z
  const double qx = in.read<double>(), qy = in.read<double>(), qz = in.read<double>(), qw = in.read<double>();
  return {x, y, detail::yawOfQuaternion(qx, qy, qz, qw)};
}

void writeStamp(detail::CdrWriter &out, double stamp) {
  const double seconds = std::floor(stamp);
  auto nanoseconds = static_cast<std::uint32_t>(std::llround((stamp - seconds) * 1e9));
  auto whole = static_cast<std::int32_t>(seconds);
  if (nanoseconds >= 1000000000u) {
    nanoseconds -= 1000000000u;
    ++whole;
  }
  out.write(whole);
  out.write(nanoseconds);
}

void writePose(detail::CdrWriter &out, const Pose2D &pose) {
  for (double value : {pose.x, pose.y, 0.0, 0.0, 0.0, std::sin(0.5 * pose.yaw), std::cos(0.5 * pose.yaw)})
    out.write(value);
}

std::vector<std::uint8_t> odometryMessage(const StampedPose &sample) {
  detail::CdrWriter out;
  writeStamp(out, sample.stamp);
  out.writeString("odom");
  out.writeString("base_link");
  writePose(out, sample.pose);
  for (int k = 0; k < 36 + 6 + 36; ++k) out.write(0.0);  // pose covariance, twist, twist covariance
  return out.bytes();
}

std::vector<std::uint8_t> scanMessage(const LaserScan &scan) {
  const detail::ScanMessage message = detail::scanMessageOf(scan);
  detail::CdrWriter out;
  writeStamp(out, message.stamp);
  out.writeString(message.frame_id);
  for (float value : {message.angle_min, message.angle_max, message.angle_increment, message.time_increment,
                      message.scan_time, message.range_min, message.range_max})
    out.write(value);
  out.writeSequence(message.ranges);
  out.writeSequence(std::vector<float>{});  // intensities
  return out.bytes();
}

std::vector<std::uint8_t> mountingMessage(double stamp, const Pose2D &mounting) {
  detail::CdrWriter out;
  out.write(std::uint32_t{1});
  writeStamp(out, stamp);
  out.writeString("base_link");
  out.writeString("laser");
  writePose(out, mounting);
  return out.bytes();
}

// What a ROS 2 bag's messages make of a log, whatever their storage: the scan and odometry
// topics are those the options name, or the first of their type.
class BagContents {
 public:
  BagContents(std::string path, const RosbagOptions &options) : path_(std::move(path)), options_(options) {
    log_.source = path_;
  }

  void topic(const std::string &name, const std::string &type) {
    if (std::find(topics_.begin(), topics_.end(), std::make_pair(name, type)) == topics_.end())
      topics_.emplace_back(name, type);
    chooseScan(name, type);
    choose(name, type, kOdometryType, options_.odometry_topic, odometry_topic_);
  }

  // A message of topic `name` in `file`; one that does not decode is reported and skipped.
  void message(const std::string &file, const std::string &name, const std::string &type, const std::uint8_t *bytes,
               std::size_t size) {
    const bool is_scan = name == scan_topic_, is_odometry = name == odometry_topic_;
    if ((!is_scan && !is_odometry && type != kTransformsType) || name.empty()) return;
    scan_met_ = scan_met_ || is_scan;
    ++index_;
    ++log_.report.lines;
    const std::string where = file + " (" + name + ")";
    if (detail::isZstdFrame(bytes, size)) {  // a bag compressed message by message
      try {
        decompressor_.decompress(bytes, size, kLargestMessage, decompressed_);
      } catch (const std::exception &e) {
        log_.report.add(where, index_, std::string("cannot decompress message: ") + e.what());
        return;
      }
      bytes = decompressed_.data();
      size = decompressed_.size();
    }
    try {
      detail::CdrReader in(bytes, size);
      if (is_scan) {
        const detail::ScanMessage scan = decodeScan(in, type);
        const bool first = log_.entries.empty();
        if (detail::addScan(scan, options_.max_range, options_.max_beams, where, index_, log_) && first)
          scan_frame_ = detail::frameName(scan.frame_id);
      } else if (is_odometry) {
        const double stamp = stampOf(in);
        in.readString();  // frame_id
        const std::string child = in.readString();
        const Pose2D pose = planarPose(in);
        if (base_frame_.empty()) base_frame_ = detail::frameName(child);
        if (std::isfinite(stamp + pose.x + pose.y + pose.yaw))
          odometry_.push_back({stamp, pose});
        else
          log_.report.add(where, index_, "odometry pose is not finite");
      } else {
        const auto count = in.read<std::uint32_t>();
        for (std::uint32_t k = 0; k < count; ++k) {
          const double stamp = stampOf(in);
          const std::string parent = in.readString(), child = in.readString();
          tree_.add(parent, child, planarPose(in), stamp);
        }
      }
    } catch (const std::exception &e) {
      log_.report.add(where, index_, std::string("cannot decode message: ") + e.what());
    }
  }

  // Messages of `file` lost at `byte` (a chunk that cannot be read).
  void lost(const std::string &file, std::uint64_t byte, const std::string &why) {
    log_.report.add(
        file, index_ + 1,
        "byte " + std::to_string(byte) + ": a chunk that cannot be read (" + why + "): its messages are not read",
        ReadReport::kAlwaysShown);
  }

  ScanLog finish() {
    requireNamed(options_.scan_topic, scan_topic_, {kScanType, kMultiEchoScanType});
    requireNamed(options_.odometry_topic, odometry_topic_, {kOdometryType});
    if (scan_topic_.empty())
      throw ReadError(path_ + ": no " + kScanType + " or " + kMultiEchoScanType + " topic in the bag");
    detail::finishBagLog(path_, tree_, scan_frame_, base_frame_, std::move(odometry_), log_);
    return std::move(log_);
  }

 private:
  static void choose(const std::string &name, const std::string &type, const char *wanted, const std::string &named,
                     std::string &chosen) {
    if (type == wanted && chosen.empty() && (named.empty() || name == named)) chosen = name;
  }
  // The scan topic: the one the options name, else the first LaserScan topic, else the first
  // MultiEchoLaserScan topic (a LaserScan topic met before any scan takes its place).
  void chooseScan(const std::string &name, const std::string &type) {
    if (type != kScanType && type != kMultiEchoScanType) return;
    const bool take = !options_.scan_topic.empty()
                          ? scan_topic_.empty() && name == options_.scan_topic
                          : scan_topic_.empty() || (type == kScanType && scan_type_ != kScanType && !scan_met_);
    if (!take) return;
    scan_topic_ = name;
    scan_type_ = type;
  }
  // A topic the options name that the bag does not carry with one of `types` is an error, so
  // that a mistyped name is not read as a bag without those messages.
  void requireNamed(const std::string &named, const std::string &chosen,
                    std::initializer_list<const char *> types) const {
    if (named.empty() || !chosen.empty()) return;
    std::string carried, wanted;
    for (const char *type : types) {
      wanted += (wanted.empty() ? "" : " or ") + std::string(type);
      for (const auto &[name, its_type] : topics_)
        if (its_type == type) carried += (carried.empty() ? "" : ", ") + name;
    }
    throw ReadError(path_ + ": no " + wanted + " topic " + named + " in the bag (" +
                    (carried.empty() ? "it has none" : "it has " + carried) + ")");
  }

  std::string path_;
  const RosbagOptions &options_;
  ScanLog log_;
  std::vector<StampedPose> odometry_;
  detail::TransformTree tree_;
  std::vector<std::pair<std::string, std::string>> topics_;  // (name, type), as met
  std::string scan_topic_, odometry_topic_;
  std::string scan_type_;                   // the scan topic's message type
  bool scan_met_ = false;                   // a message of the scan topic has been read
  std::string scan_frame_, base_frame_;     // of the first scan and the first odometry message
  std::size_t index_ = 0;                   // messages of the topics read, counted from 1
  detail::ZstdDecompressor decompressor_;   // for messages compressed on their own
  std::vector<std::uint8_t> decompressed_;  // a compressed message's bytes
};

// The storage file at `path` read as the kind `name`'s extension says: MCAP or sqlite3.
void visitStorage(const std::string &path, const std::string &name, const detail::StorageVisitor &visitor) {
  if (fs::path(name).extension() == ".mcap")
    detail::visitMcap(path, visitor);
  else
    detail::visitSqlite(path, visitor);
}

// The topics and messages of one storage file into `contents`.
void readStorageFile(const std::string &file, BagContents &contents) {
  std::map<std::uint16_t, detail::StoredTopic> topics;
  detail::StorageVisitor visitor;
  visitor.topic = [&](const detail::StoredTopic &topic) {
    topics[topic.id] = topic;
    contents.topic(topic.name, topic.type);
  };
  visitor.message = [&](std::uint16_t id, const std::uint8_t *data, std::size_t size) {
    const auto topic = topics.find(id);
    if (topic != topics.end()) contents.message(file, topic->second.name, topic->second.type, data, size);
  };
  visitor.lost = [&](std::uint64_t byte, const std::string &why) { contents.lost(file, byte, why); };
  const std::string stored = detail::withoutZstd(file);
  if (!detail::isZstdFile(file)) {
    visitStorage(file, stored, visitor);
    return;
  }
  // Compressed whole: read decompressed, and named as the compressed file.
  const detail::DecompressedFile decompressed(file);
  try {
    visitStorage(decompressed.path(), stored, visitor);
  } catch (const ReadError &error) {
    std::string what = error.what();
    for (std::size_t at = what.find(decompressed.path()); at != std::string::npos;
         at = what.find(decompressed.path(), at + file.size()))
      what.replace(at, decompressed.path().size(), file);
    throw ReadError(what);
  }
}

}  // namespace

bool isRosbag2(const std::string &path) {
  std::error_code error;
  const fs::path p(path);
  if (!fs::is_directory(p, error)) return isStorageFile(p);
  if (fs::exists(p / "metadata.yaml", error)) return true;
  for (const fs::directory_entry &entry : fs::directory_iterator(p, error))
    if (isStorageFile(entry.path())) return true;
  return false;
}

ScanLog readRosbag2(const std::string &path, const RosbagOptions &options) {
  BagContents contents(path, options);
  for (const std::string &file : storageFiles(path)) {
    std::error_code error;
    if (!fs::is_regular_file(file, error)) throw ReadError(file + ": no such storage file of the ROS 2 bag");
    readStorageFile(file, contents);
  }
  return contents.finish();
}

void writeRosbag2(const std::string &path, const ScanLog &log) {
  const std::vector<detail::StoredTopic> topics = {
      {1, "/scan", "cdr", kScanType}, {2, "/odom", "cdr", kOdometryType}, {3, "/tf_static", "cdr", kTransformsType}};
  std::vector<detail::StoredMessage> messages;
  const auto put = [&](std::size_t topic, double stamp, std::vector<std::uint8_t> data, const std::string &what) {
    if (!(stamp >= 0.0) || !(stamp < 2147483648.0))
      throw ReadError(path + ": " + what + " has stamp " + std::to_string(stamp) + " s, which a bag cannot hold");
    messages.push_back({topic, static_cast<std::uint64_t>(std::llround(stamp * 1e9)), std::move(data)});
  };
  const std::vector<StampedPose> samples = detail::odometryToWrite(log);
  std::size_t next_odometry = 0;
  for (std::size_t k = 0; k < log.entries.size(); ++k) {
    const LaserScan &scan = log.entries[k].scan;
    if (k == 0 && log.laser_pose) put(2, scan.stamp, mountingMessage(scan.stamp, *log.laser_pose), "the mounting");
    for (; next_odometry < samples.size() && samples[next_odometry].stamp <= scan.stamp; ++next_odometry)
      put(1, samples[next_odometry].stamp, odometryMessage(samples[next_odometry]),
          "odometry sample " + std::to_string(next_odometry));
    put(0, scan.stamp, scanMessage(scan), "scan " + std::to_string(k));
  }
  for (; next_odometry < samples.size(); ++next_odometry)
    put(1, samples[next_odometry].stamp, odometryMessage(samples[next_odometry]),
        "odometry sample " + std::to_string(next_odometry));
  if (fs::path(path).extension() == ".mcap")
    detail::writeMcap(path, topics, messages, "zstd");
  else
    detail::writeSqlite(path, topics, messages);
}

}  // namespace contour_reg::io
