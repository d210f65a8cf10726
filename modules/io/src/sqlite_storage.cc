#include "sqlite_storage.h"

#include <sqlite3.h>

#include <cstdint>
#include <filesystem>
#include <map>

#include "contour_reg/io/scan_log.h"

namespace contour_reg::io::detail {

namespace {

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

}  // namespace

void visitSqlite(const std::string &path, const StorageVisitor &visitor) {
  const Database db(path, SQLITE_OPEN_READONLY);
  std::map<std::int64_t, std::uint16_t> ids;  // the table's topic id -> the visitor's
  {
    Statement query(db, "SELECT id, name, type FROM topics ORDER BY id", "not a readable ROS 2 bag");
    while (sqlite3_step(query.get()) == SQLITE_ROW) {
      if (ids.size() == 0xffff) throw ReadError(path + ": more topics than a ROS 2 bag holds");
      StoredTopic topic;
      topic.id = static_cast<std::uint16_t>(ids.size() + 1);
      ids[sqlite3_column_int64(query.get(), 0)] = topic.id;
      const auto *name = reinterpret_cast<const char *>(sqlite3_column_text(query.get(), 1));
      const auto *type = reinterpret_cast<const char *>(sqlite3_column_text(query.get(), 2));
      topic.name = name ? name : "";
      topic.type = type ? type : "";
      topic.message_encoding = "cdr";
      if (visitor.topic) visitor.topic(topic);
    }
  }
  Statement messages(db, "SELECT topic_id, data FROM messages ORDER BY timestamp, id", "not a readable ROS 2 bag");
  int step = SQLITE_ROW;
  while ((step = sqlite3_step(messages.get())) == SQLITE_ROW) {
    const auto id = ids.find(sqlite3_column_int64(messages.get(), 0));
    if (id == ids.end()) continue;
    const auto *bytes = static_cast<const std::uint8_t *>(sqlite3_column_blob(messages.get(), 1));
    const auto size = static_cast<std::size_t>(sqlite3_column_bytes(messages.get(), 1));
    if (visitor.message) visitor.message(id->second, bytes, bytes ? size : 0);
  }
  if (step != SQLITE_DONE) db.fail("not a readable ROS 2 bag");
}

void writeSqlite(const std::string &path, const std::vector<StoredTopic> &topics,
                 const std::vector<StoredMessage> &messages) {
  std::error_code error;
  std::filesystem::remove(path, error);  // a bag is written anew
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
    sqlite3_bind_text(topic.get(), 2, topics[k].name.c_str(), -1, SQLITE_TRANSIENT);
    sqlite3_bind_text(topic.get(), 3, topics[k].type.c_str(), -1, SQLITE_TRANSIENT);
    if (sqlite3_step(topic.get()) != SQLITE_DONE) db.fail("cannot write the bag");
  }
  Statement insert(db, "INSERT INTO messages(topic_id, timestamp, data) VALUES(?, ?, ?)", "cannot write the bag");
  for (const StoredMessage &message : messages) {
    sqlite3_reset(insert.get());
    sqlite3_bind_int64(insert.get(), 1, static_cast<std::int64_t>(message.topic + 1));
    sqlite3_bind_int64(insert.get(), 2, static_cast<std::int64_t>(message.log_time));
    sqlite3_bind_blob(insert.get(), 3, message.data.data(), static_cast<int>(message.data.size()), SQLITE_TRANSIENT);
    if (sqlite3_step(insert.get()) != SQLITE_DONE) db.fail("cannot write the bag");
  }
  db.execute("COMMIT;");
}

}  // namespace contour_reg::io::detail
