// rosbag2 sqlite3 storage, every schema from Dashing to Jazzy:
//   schema 1 (Dashing..Foxy): topics(id, name, type, serialization_format
//     [, offered_qos_profiles]), messages(id, topic_id, timestamp, data); no schema table
//   schema 2/3 (Galactic, Humble): + schema(schema_version, ros_distro), metadata table
//   schema 4 (Iron, Jazzy): + topics.type_description_hash, message_definitions table
// Columns are discovered with PRAGMA table_info, so a variant in between reads too.
#include <set>
#include <unordered_map>

#include "core/errors.h"
#include "core/log.h"
#include "drivers/rosbag/bag_storage.h"
#include "drivers/rosbag/sqlite_util.h"

namespace uwbsar::rosbag {
namespace {

// A writer killed inside a transaction whose pages had already spilled into the file
// (our live recorder after kill -9, between two flushes) leaves a hot rollback journal,
// `<file>-journal`. sqlite will not read such a file read-only (SQLITE_READONLY_ROLLBACK):
// the journal must first be played back, which restores the last commit, i.e. exactly
// what the recording promises (everything up to its last flush). Does that once with a
// read-write connection and returns `path`; a file that reads read-only is left untouched.
const std::string& RolledBackAfterCrash(const std::string& path) {
  int code = SQLITE_OK;
  {
    sqlite3* db = nullptr;
    sqlite3_stmt* stmt = nullptr;
    if (sqlite3_open_v2(path.c_str(), &db, SQLITE_OPEN_READONLY, nullptr) == SQLITE_OK) {
      sqlite3_extended_result_codes(db, 1);
      if (sqlite3_prepare_v2(db, "SELECT count(*) FROM sqlite_master", -1, &stmt, nullptr) ==
          SQLITE_OK) {
        sqlite3_step(stmt);
      }
      code = sqlite3_extended_errcode(db);
    }
    sqlite3_finalize(stmt);
    sqlite3_close(db);
  }
  if (code != SQLITE_READONLY_ROLLBACK) return path;  // other errors: the real open names them
  try {
    SqliteDb db(path, SQLITE_OPEN_READWRITE);
    db.Exec("SELECT count(*) FROM sqlite_master");  // the first read plays the journal back
  } catch (const std::exception& e) {
    throw InputError(path + ": holds a transaction interrupted by a crash (" + path +
                     "-journal) that needs write access to roll back: " + e.what());
  }
  Log(LogLevel::kWarning, path + ": rolled back a transaction interrupted by a crash; " +
                              "the file holds everything up to its writer's last commit");
  return path;
}

class SqliteStorageReader final : public StorageReader {
 public:
  explicit SqliteStorageReader(const std::string& path)
      : db_(RolledBackAfterCrash(path), SQLITE_OPEN_READONLY | SQLITE_OPEN_NOMUTEX) {
    std::set<std::string> tables;
    {
      SqliteStatement q(db_, "SELECT name FROM sqlite_master WHERE type='table'");
      while (q.Step()) tables.insert(q.Text(0));
    }
    for (const char* required : {"topics", "messages"}) {
      if (!tables.count(required)) {
        throw InputError(path + ": not a rosbag2 sqlite3 file: no '" + std::string(required) +
                         "' table");
      }
    }
    std::set<std::string> columns;
    {
      SqliteStatement q(db_, "PRAGMA table_info(topics)");
      while (q.Step()) columns.insert(q.Text(1));
    }
    for (const char* required : {"id", "name", "type", "serialization_format"}) {
      if (!columns.count(required)) {
        throw InputError(path + ": not a rosbag2 sqlite3 file: table 'topics' has no '" +
                         std::string(required) + "' column");
      }
    }
    const bool has_qos = columns.count("offered_qos_profiles") > 0;
    const bool has_hash = columns.count("type_description_hash") > 0;
    std::string sql = "SELECT id, name, type, serialization_format";
    sql += has_qos ? ", offered_qos_profiles" : ", ''";
    sql += has_hash ? ", type_description_hash" : ", ''";
    sql += " FROM topics ORDER BY id";
    SqliteStatement q(db_, sql);
    while (q.Step()) {
      TopicInfo t;
      t.name = q.Text(1);
      t.type = q.Text(2);
      t.serialization_format = q.Text(3);
      t.offered_qos_profiles = q.Text(4);
      t.type_description_hash = q.Text(5);
      topic_index_[q.Int(0)] = static_cast<int>(topics_.size());
      topics_.push_back(std::move(t));
    }
    if (tables.count("message_definitions")) ReadDefinitions();
  }

  const std::string& Path() const override { return db_.path(); }
  const char* StorageId() const override { return "sqlite3"; }

  const std::vector<TopicInfo>& Topics() override { return topics_; }

  StorageStats Stats() override {
    Count();
    return stats_;
  }

  bool Next(StorageMessage* msg) override {
    if (!messages_) {
      // The rosbag2 timestamp index makes this a streaming walk, not a sort.
      messages_ = std::make_unique<SqliteStatement>(
          db_, "SELECT topic_id, timestamp, data FROM messages ORDER BY timestamp, id");
    }
    if (!messages_->Step()) return false;
    const std::int64_t topic_id = messages_->Int(0);
    const auto it = topic_index_.find(topic_id);
    if (it == topic_index_.end()) {
      throw InputError(Path() + ": message at timestamp " + std::to_string(messages_->Int(1)) +
                       " refers to topic_id " + std::to_string(topic_id) +
                       " which is not in the topics table");
    }
    msg->topic = it->second;
    msg->log_time_ns = messages_->Int(1);
    msg->data = static_cast<const std::uint8_t*>(sqlite3_column_blob(messages_->get(), 2));
    msg->size = static_cast<std::size_t>(sqlite3_column_bytes(messages_->get(), 2));
    return true;
  }

 private:
  void ReadDefinitions() {
    std::unordered_map<std::string, std::pair<std::string, std::string>> defs;
    SqliteStatement q(db_,
                      "SELECT topic_type, encoding, encoded_message_definition "
                      "FROM message_definitions");
    while (q.Step()) defs[q.Text(0)] = {q.Text(1), q.Text(2)};
    for (auto& t : topics_) {
      const auto it = defs.find(t.type);
      if (it == defs.end()) continue;
      t.definition_encoding = it->second.first;
      t.message_definition = it->second.second;
    }
  }

  void Count() {
    if (counted_) return;
    SqliteStatement q(db_,
                      "SELECT topic_id, COUNT(*), MIN(timestamp), MAX(timestamp) FROM messages "
                      "GROUP BY topic_id");
    bool first = true;
    while (q.Step()) {
      const auto it = topic_index_.find(q.Int(0));
      if (it == topic_index_.end()) {
        throw InputError(Path() + ": messages refer to topic_id " + std::to_string(q.Int(0)) +
                         " which is not in the topics table");
      }
      const auto n = static_cast<std::uint64_t>(q.Int(1));
      topics_[static_cast<std::size_t>(it->second)].message_count = n;
      stats_.message_count += n;
      stats_.start_ns = first ? q.Int(2) : std::min(stats_.start_ns, q.Int(2));
      stats_.end_ns = first ? q.Int(3) : std::max(stats_.end_ns, q.Int(3));
      first = false;
    }
    counted_ = true;
  }

  SqliteDb db_;
  std::vector<TopicInfo> topics_;
  std::unordered_map<std::int64_t, int> topic_index_;
  StorageStats stats_;
  bool counted_ = false;
  std::unique_ptr<SqliteStatement> messages_;
};

}  // namespace

std::unique_ptr<StorageReader> OpenSqliteStorage(const std::string& path) {
  return std::make_unique<SqliteStorageReader>(path);
}

}  // namespace uwbsar::rosbag
