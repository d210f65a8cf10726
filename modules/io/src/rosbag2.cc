#include "contour_reg/io/rosbag2.h"

#include <sqlite3.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <map>
#include <stdexcept>
#include <vector>

#include "bag_messages.h"
#include "cdr.h"
#include "log_assembly.h"
#include "mcap.h"

namespace contour_reg::io {

namespace {

namespace fs = std::filesystem;

constexpr char kScanType[] = "sensor_msgs/msg/LaserScan";
constexpr char kOdometryType[] = "nav_msgs/msg/Odometry";
constexpr char kTransformsType[] = "tf2_msgs/msg/TFMessage";

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
      for (const YAML::Node &file : information["relative_file_paths"])
        files.push_back((folder / file.as<std::string>()).string());
    } catch (const YAML::Exception &e) {
      const std::string line = e.mark.line >= 0 ? ":" + std::to_string(e.mark.line + 1) : "";
      throw ReadError(metadata.string() + line + ": " + e.msg);
    }
  } else {
    for (const fs::directory_entry &entry : fs::directory_iterator(folder, error))
      if (entry.path().extension() == ".db3" || entry.path().extension() == ".mcap")
        files.push_back(entry.path().string());
    std::sort(files.begin(), files.end());
  }
  if (files.empty()) throw ReadError(path + ": a ROS 2 bag folder without a storage file");
  return files;
}

class Database {
 public:
  Database(const std::string &path, int flags) : path_(path) {
    if (sqlite3_open_v2(path.c_str(), &db_, flags, nullptr) == SQLITE_OK) return;
    const std::string why = db_ ? sqlite3_errmsg(db_) : "out of memory";
    sqlite3_close(db_);
    throw ReadError(path + ": cannot open: " + why);
  }
  ~Database() { sqlite3_close(db_); }
  Database(const Database &) = delete;
  Database &operator=(const Database &) = delete;

  sqlite3 *get() const { return db_; }
  [[noreturn]] void fail(const std::string &what) const {
    throw ReadError(path_ + ": " + what + ": " + (db_ ? sqlite3_errmsg(db_) : "out of memory"));
  }
  void execute(const char *sql) const {
    if (sqlite3_exec(db_, sql, nullptr, nullptr, nullptr) != SQLITE_OK) fail("cannot write the bag");
  }

 private:
  std::string path_;
  sqlite3 *db_ = nullptr;
};

class Statement {
 public:
  Statement(const Database &db, const char *sql, const std::string &what) {
    if (sqlite3_prepare_v2(db.get(), sql, -1, &statement_, nullptr) != SQLITE_OK) db.fail(what);
  }
  ~Statement() { sqlite3_finalize(statement_); }
  Statement(const Statement &) = delete;
  Statement &operator=(const Statement &) = delete;
  sqlite3_stmt *get() const { return statement_; }

 private:
  sqlite3_stmt *statement_ = nullptr;
};

double stampOf(detail::CdrReader &in) {
  const auto seconds = in.read<std::int32_t>();
  const auto nanoseconds = in.read<std::uint32_t>();
  return seconds + 1e-9 * nanoseconds;
}

detail::ScanMessage decodeScan(detail::CdrReader &in) {
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
  scan.ranges = in.readSequence<float>();
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
    choose(name, type, kScanType, options_.scan_topic, scan_topic_);
    choose(name, type, kOdometryType, options_.odometry_topic, odometry_topic_);
  }

  // A message of topic `name` in `file`; one that does not decode is reported and skipped.
  void message(const std::string &file, const std::string &name, const std::string &type, const std::uint8_t *bytes,
               std::size_t size) {
    const bool is_scan = name == scan_topic_, is_odometry = name == odometry_topic_;
    if ((!is_scan && !is_odometry && type != kTransformsType) || name.empty()) return;
    ++index_;
    ++log_.report.lines;
    const std::string where = file + " (" + name + ")";
    try {
      detail::CdrReader in(bytes, bytes ? size : 0);
      if (is_scan) {
        const detail::ScanMessage scan = decodeScan(in);
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
          stampOf(in);
          const std::string parent = in.readString(), child = in.readString();
          tree_.add(parent, child, planarPose(in));
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
    requireNamed(options_.scan_topic, scan_topic_, kScanType);
    requireNamed(options_.odometry_topic, odometry_topic_, kOdometryType);
    if (scan_topic_.empty()) throw ReadError(path_ + ": no " + std::string(kScanType) + " topic in the bag");
    detail::finishBagLog(path_, tree_, scan_frame_, base_frame_, std::move(odometry_), log_);
    return std::move(log_);
  }

 private:
  static void choose(const std::string &name, const std::string &type, const char *wanted, const std::string &named,
                     std::string &chosen) {
    if (type == wanted && chosen.empty() && (named.empty() || name == named)) chosen = name;
  }
  // A topic the options name that the bag does not carry with its type is an error, so that a
  // mistyped name is not read as a bag without those messages.
  void requireNamed(const std::string &named, const std::string &chosen, const char *type) const {
    if (named.empty() || !chosen.empty()) return;
    std::string carried;
    for (const auto &[name, its_type] : topics_)
      if (its_type == type) carried += (carried.empty() ? "" : ", ") + name;
    throw ReadError(path_ + ": no " + type + " topic " + named + " in the bag (" +
                    (carried.empty() ? "it has none" : "it has " + carried) + ")");
  }

  std::string path_;
  const RosbagOptions &options_;
  ScanLog log_;
  std::vector<StampedPose> odometry_;
  detail::TransformTree tree_;
  std::vector<std::pair<std::string, std::string>> topics_;  // (name, type), as met
  std::string scan_topic_, odometry_topic_;
  std::string scan_frame_, base_frame_;  // of the first scan and the first odometry message
  std::size_t index_ = 0;                // messages of the topics read, counted from 1
};

void readSqliteFile(const std::string &file, BagContents &contents) {
  const Database db(file, SQLITE_OPEN_READONLY);
  std::map<std::int64_t, std::pair<std::string, std::string>> topics;  // id -> (name, type)
  {
    Statement query(db, "SELECT id, name, type FROM topics ORDER BY id", "not a readable ROS 2 bag");
    while (sqlite3_step(query.get()) == SQLITE_ROW) {
      const auto *name = reinterpret_cast<const char *>(sqlite3_column_text(query.get(), 1));
      const auto *type = reinterpret_cast<const char *>(sqlite3_column_text(query.get(), 2));
      auto &topic = topics[sqlite3_column_int64(query.get(), 0)] = {name ? name : "", type ? type : ""};
      contents.topic(topic.first, topic.second);
    }
  }
  Statement messages(db, "SELECT topic_id, data FROM messages ORDER BY timestamp, id", "not a readable ROS 2 bag");
  int step = SQLITE_ROW;
  while ((step = sqlite3_step(messages.get())) == SQLITE_ROW) {
    const auto topic = topics.find(sqlite3_column_int64(messages.get(), 0));
    if (topic == topics.end()) continue;
    const auto *bytes = static_cast<const std::uint8_t *>(sqlite3_column_blob(messages.get(), 1));
    const auto size = static_cast<std::size_t>(sqlite3_column_bytes(messages.get(), 1));
    contents.message(file, topic->second.first, topic->second.second, bytes, size);
  }
  if (step != SQLITE_DONE) db.fail("not a readable ROS 2 bag");
}

void readMcapFile(const std::string &file, BagContents &contents) {
  std::map<std::uint16_t, detail::McapChannel> channels;
  detail::McapVisitor visitor;
  visitor.channel = [&](const detail::McapChannel &channel) {
    channels[channel.id] = channel;
    contents.topic(channel.topic, channel.schema_name);
  };
  visitor.message = [&](std::uint16_t id, const std::uint8_t *data, std::size_t size) {
    const auto channel = channels.find(id);
    if (channel != channels.end())
      contents.message(file, channel->second.topic, channel->second.schema_name, data, size);
  };
  visitor.unreadable_chunk = [&](std::uint64_t byte, const std::string &why) { contents.lost(file, byte, why); };
  detail::visitMcap(file, visitor);
}

// The messages as rosbag2's sqlite3 storage (schema version 3, ROS 2 Humble) keeps them.
void writeSqlite(const std::string &path, const std::vector<detail::McapChannel> &topics,
                 const std::vector<detail::McapMessage> &messages) {
  std::error_code error;
  fs::remove(path, error);  // a bag is written anew
  const Database db(path, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE);
  db.execute(
      "CREATE TABLE schema(schema_version INTEGER PRIMARY KEY, ros_distro TEXT NOT NULL);"
      "INSERT INTO schema VALUES(3, 'humble');"
      "CREATE TABLE topics(id INTEGER PRIMARY KEY, name TEXT NOT NULL, type TEXT NOT NULL,"
      " serialization_format TEXT NOT NULL, offered_qos_profiles TEXT NOT NULL);"
      "CREATE TABLE messages(id INTEGER PRIMARY KEY, topic_id INTEGER NOT NULL, timestamp INTEGER NOT NULL,"
      " data BLOB NOT NULL);"
      "CREATE INDEX timestamp_idx ON messages (timestamp ASC);"
      "BEGIN;");
  Statement topic(db, "INSERT INTO topics VALUES(?, ?, ?, 'cdr', '')", "cannot write the bag");
  for (std::size_t k = 0; k < topics.size(); ++k) {
    sqlite3_reset(topic.get());
    sqlite3_bind_int64(topic.get(), 1, static_cast<std::int64_t>(k + 1));
    sqlite3_bind_text(topic.get(), 2, topics[k].topic.c_str(), -1, SQLITE_TRANSIENT);
    sqlite3_bind_text(topic.get(), 3, topics[k].schema_name.c_str(), -1, SQLITE_TRANSIENT);
    if (sqlite3_step(topic.get()) != SQLITE_DONE) db.fail("cannot write the bag");
  }
  Statement insert(db, "INSERT INTO messages(topic_id, timestamp, data) VALUES(?, ?, ?)", "cannot write the bag");
  for (const detail::McapMessage &message : messages) {
    sqlite3_reset(insert.get());
    sqlite3_bind_int64(insert.get(), 1, static_cast<std::int64_t>(message.channel + 1));
    sqlite3_bind_int64(insert.get(), 2, static_cast<std::int64_t>(message.log_time));
    sqlite3_bind_blob(insert.get(), 3, message.data.data(), static_cast<int>(message.data.size()), SQLITE_TRANSIENT);
    if (sqlite3_step(insert.get()) != SQLITE_DONE) db.fail("cannot write the bag");
  }
  db.execute("COMMIT;");
}

}  // namespace

bool isRosbag2(const std::string &path) {
  std::error_code error;
  const fs::path p(path);
  if (!fs::is_directory(p, error)) return p.extension() == ".db3" || p.extension() == ".mcap";
  if (fs::exists(p / "metadata.yaml", error)) return true;
  for (const fs::directory_entry &entry : fs::directory_iterator(p, error))
    if (entry.path().extension() == ".db3" || entry.path().extension() == ".mcap") return true;
  return false;
}

ScanLog readRosbag2(const std::string &path, const RosbagOptions &options) {
  BagContents contents(path, options);
  for (const std::string &file : storageFiles(path)) {
    std::error_code error;
    if (!fs::is_regular_file(file, error)) throw ReadError(file + ": no such storage file of the ROS 2 bag");
    if (fs::path(file).extension() == ".mcap")
      readMcapFile(file, contents);
    else
      readSqliteFile(file, contents);
  }
  return contents.finish();
}

void writeRosbag2(const std::string &path, const ScanLog &log) {
  const std::vector<detail::McapChannel> topics = {
      {1, "/scan", "cdr", kScanType}, {2, "/odom", "cdr", kOdometryType}, {3, "/tf_static", "cdr", kTransformsType}};
  std::vector<detail::McapMessage> messages;
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
    writeSqlite(path, topics, messages);
}

}  // namespace contour_reg::io
