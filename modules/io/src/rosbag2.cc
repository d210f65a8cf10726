#include "contour_reg/io/rosbag2.h"

#include <sqlite3.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <vector>

#include "bag_messages.h"
#include "cdr.h"
#include "log_assembly.h"

namespace contour_reg::io {

namespace {

namespace fs = std::filesystem;

constexpr char kScanType[] = "sensor_msgs/msg/LaserScan";
constexpr char kOdometryType[] = "nav_msgs/msg/Odometry";
constexpr char kTransformsType[] = "tf2_msgs/msg/TFMessage";

std::string notSqlite(const std::string &path, const std::string &storage) {
  return path + ": a ROS 2 bag in " + storage +
         " storage; this build reads the sqlite3 storage (.db3): convert the bag with `ros2 bag convert`";
}

// The storage files of the bag at `path`, in the order they were recorded.
std::vector<std::string> storageFiles(const std::string &path) {
  std::error_code error;
  if (!fs::is_directory(path, error)) {
    if (fs::path(path).extension() == ".mcap") throw ReadError(notSqlite(path, "MCAP"));
    return {path};
  }
  const fs::path folder(path), metadata = folder / "metadata.yaml";
  std::vector<std::string> files;
  if (fs::exists(metadata, error)) {
    try {
      const YAML::Node information = YAML::LoadFile(metadata.string())["rosbag2_bagfile_information"];
      if (!information) throw ReadError(metadata.string() + ": no rosbag2_bagfile_information");
      const std::string storage = information["storage_identifier"].as<std::string>("sqlite3");
      if (storage != "sqlite3") throw ReadError(notSqlite(path, storage));
      for (const YAML::Node &file : information["relative_file_paths"])
        files.push_back((folder / file.as<std::string>()).string());
    } catch (const YAML::Exception &e) {
      const std::string line = e.mark.line >= 0 ? ":" + std::to_string(e.mark.line + 1) : "";
      throw ReadError(metadata.string() + line + ": " + e.msg);
    }
  } else {
    for (const fs::directory_entry &entry : fs::directory_iterator(folder, error))
      if (entry.path().extension() == ".db3") files.push_back(entry.path().string());
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

struct Topic {
  std::int64_t id;
  std::string name, type;
};

std::vector<Topic> topicsOf(const Database &db) {
  Statement query(db, "SELECT id, name, type FROM topics ORDER BY id", "not a readable ROS 2 bag");
  std::vector<Topic> topics;
  while (sqlite3_step(query.get()) == SQLITE_ROW) {
    const auto *name = reinterpret_cast<const char *>(sqlite3_column_text(query.get(), 1));
    const auto *type = reinterpret_cast<const char *>(sqlite3_column_text(query.get(), 2));
    topics.push_back({sqlite3_column_int64(query.get(), 0), name ? name : "", type ? type : ""});
  }
  return topics;
}

// The topic the options name, or the bag's first of `type` when they name none; a named topic
// the bag does not carry with that type is an error, as for ROS 1 bags.
std::string topicToRead(const std::vector<Topic> &topics, const std::string &path, const std::string &named,
                        const std::string &type) {
  std::string carried;
  for (const Topic &topic : topics) {
    if (topic.type != type) continue;
    if (named.empty() || topic.name == named) return topic.name;
    carried += (carried.empty() ? "" : ", ") + topic.name;
  }
  if (named.empty()) return {};
  throw ReadError(path + ": no " + type + " topic " + named + " in the bag (" +
                  (carried.empty() ? "it has none" : "it has " + carried) + ")");
}

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

}  // namespace

bool isRosbag2(const std::string &path) {
  std::error_code error;
  const fs::path p(path);
  if (!fs::is_directory(p, error)) return p.extension() == ".db3" || p.extension() == ".mcap";
  if (fs::exists(p / "metadata.yaml", error)) return true;
  for (const fs::directory_entry &entry : fs::directory_iterator(p, error))
    if (entry.path().extension() == ".db3") return true;
  return false;
}

ScanLog readRosbag2(const std::string &path, const RosbagOptions &options) {
  ScanLog log;
  log.source = path;
  std::vector<StampedPose> odometry;
  detail::TransformTree tree;
  std::string scan_frame, base_frame;  // of the first scan and the first odometry message
  std::size_t index = 0;
  bool any_scan_topic = false;
  for (const std::string &file : storageFiles(path)) {
    std::error_code error;
    if (!fs::is_regular_file(file, error)) throw ReadError(file + ": no such storage file of the ROS 2 bag");
    const Database db(file, SQLITE_OPEN_READONLY);
    const std::vector<Topic> topics = topicsOf(db);
    const std::string scan_topic = topicToRead(topics, file, options.scan_topic, kScanType);
    const std::string odometry_topic = topicToRead(topics, file, options.odometry_topic, kOdometryType);
    any_scan_topic |= !scan_topic.empty();
    Statement messages(db, "SELECT topic_id, data FROM messages ORDER BY timestamp, id", "not a readable ROS 2 bag");
    int step = SQLITE_ROW;
    while ((step = sqlite3_step(messages.get())) == SQLITE_ROW) {
      const std::int64_t topic_id = sqlite3_column_int64(messages.get(), 0);
      const auto topic = std::find_if(topics.begin(), topics.end(), [&](const Topic &t) { return t.id == topic_id; });
      if (topic == topics.end()) continue;
      const bool is_scan = topic->name == scan_topic, is_odometry = topic->name == odometry_topic;
      if (!is_scan && !is_odometry && topic->type != kTransformsType) continue;
      ++index;
      ++log.report.lines;
      const std::string where = file + " (" + topic->name + ")";
      const auto *bytes = static_cast<const std::uint8_t *>(sqlite3_column_blob(messages.get(), 1));
      const auto size = static_cast<std::size_t>(sqlite3_column_bytes(messages.get(), 1));
      try {
        detail::CdrReader in(bytes, bytes ? size : 0);
        if (is_scan) {
          const detail::ScanMessage scan = decodeScan(in);
          const bool first = log.entries.empty();
          if (detail::addScan(scan, options.max_range, options.max_beams, where, index, log) && first)
            scan_frame = detail::frameName(scan.frame_id);
        } else if (is_odometry) {
          const double stamp = stampOf(in);
          in.readString();  // frame_id
          const std::string child = in.readString();
          const Pose2D pose = planarPose(in);
          if (base_frame.empty()) base_frame = detail::frameName(child);
          if (std::isfinite(stamp + pose.x + pose.y + pose.yaw))
            odometry.push_back({stamp, pose});
          else
            log.report.add(where, index, "odometry pose is not finite");
        } else {
          const auto count = in.read<std::uint32_t>();
          for (std::uint32_t k = 0; k < count; ++k) {
            stampOf(in);
            const std::string parent = in.readString(), child = in.readString();
            tree.add(parent, child, planarPose(in));
          }
        }
      } catch (const std::exception &e) {
        log.report.add(where, index, std::string("cannot decode message: ") + e.what());
      }
    }
    if (step != SQLITE_DONE) db.fail("not a readable ROS 2 bag");
  }
  if (!any_scan_topic) throw ReadError(path + ": no " + std::string(kScanType) + " topic in the bag");
  detail::finishBagLog(path, tree, scan_frame, base_frame, std::move(odometry), log);
  return log;
}

void writeRosbag2(const std::string &path, const ScanLog &log) {
  std::error_code error;
  fs::remove(path, error);  // a bag is written anew
  const Database db(path, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE);
  // The schema of rosbag2's sqlite3 storage (version 3, ROS 2 Humble).
  db.execute(
      "CREATE TABLE schema(schema_version INTEGER PRIMARY KEY, ros_distro TEXT NOT NULL);"
      "INSERT INTO schema VALUES(3, 'humble');"
      "CREATE TABLE topics(id INTEGER PRIMARY KEY, name TEXT NOT NULL, type TEXT NOT NULL,"
      " serialization_format TEXT NOT NULL, offered_qos_profiles TEXT NOT NULL);"
      "CREATE TABLE messages(id INTEGER PRIMARY KEY, topic_id INTEGER NOT NULL, timestamp INTEGER NOT NULL,"
      " data BLOB NOT NULL);"
      "CREATE INDEX timestamp_idx ON messages (timestamp ASC);"
      "INSERT INTO topics VALUES(1, '/scan', 'sensor_msgs/msg/LaserScan', 'cdr', '');"
      "INSERT INTO topics VALUES(2, '/odom', 'nav_msgs/msg/Odometry', 'cdr', '');"
      "INSERT INTO topics VALUES(3, '/tf_static', 'tf2_msgs/msg/TFMessage', 'cdr', '');"
      "BEGIN;");
  Statement insert(db, "INSERT INTO messages(topic_id, timestamp, data) VALUES(?, ?, ?)", "cannot write the bag");
  const auto put = [&](int topic, double stamp, const std::vector<std::uint8_t> &data, const std::string &what) {
    if (!(stamp >= 0.0) || !(stamp < 2147483648.0))
      throw ReadError(path + ": " + what + " has stamp " + std::to_string(stamp) + " s, which a bag cannot hold");
    sqlite3_reset(insert.get());
    sqlite3_bind_int(insert.get(), 1, topic);
    sqlite3_bind_int64(insert.get(), 2, std::llround(stamp * 1e9));
    sqlite3_bind_blob(insert.get(), 3, data.data(), static_cast<int>(data.size()), SQLITE_TRANSIENT);
    if (sqlite3_step(insert.get()) != SQLITE_DONE) db.fail("cannot write the bag");
  };
  const std::vector<StampedPose> samples = detail::odometryToWrite(log);
  std::size_t next_odometry = 0;
  for (std::size_t k = 0; k < log.entries.size(); ++k) {
    const LaserScan &scan = log.entries[k].scan;
    if (k == 0 && log.laser_pose) put(3, scan.stamp, mountingMessage(scan.stamp, *log.laser_pose), "the mounting");
    for (; next_odometry < samples.size() && samples[next_odometry].stamp <= scan.stamp; ++next_odometry)
      put(2, samples[next_odometry].stamp, odometryMessage(samples[next_odometry]),
          "odometry sample " + std::to_string(next_odometry));
    put(1, scan.stamp, scanMessage(scan), "scan " + std::to_string(k));
  }
  for (; next_odometry < samples.size(); ++next_odometry)
    put(2, samples[next_odometry].stamp, odometryMessage(samples[next_odometry]),
        "odometry sample " + std::to_string(next_odometry));
  db.execute("COMMIT;");
}

}  // namespace contour_reg::io
