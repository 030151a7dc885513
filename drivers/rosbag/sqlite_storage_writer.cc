// rosbag2 sqlite3 storage in the Humble layout (schema 3): what `ros2 bag` of Humble
// writes and every later distro reads. Messages go into one open transaction that
// Flush() commits, so a crash loses at most the messages since the last flush.
#include "core/errors.h"
#include "drivers/rosbag/bag_storage.h"
#include "drivers/rosbag/sqlite_util.h"

namespace uwbsar::rosbag {
namespace {

constexpr const char* kHumbleSchema =
    "CREATE TABLE schema(schema_version INTEGER PRIMARY KEY,ros_distro TEXT NOT NULL);"
    "INSERT INTO schema VALUES(3,'humble');"
    "CREATE TABLE metadata(id INTEGER PRIMARY KEY,metadata_version INTEGER NOT NULL,"
    "metadata TEXT NOT NULL);"
    "CREATE TABLE topics(id INTEGER PRIMARY KEY,name TEXT NOT NULL,type TEXT NOT NULL,"
    "serialization_format TEXT NOT NULL,offered_qos_profiles TEXT NOT NULL);"
    "CREATE TABLE messages(id INTEGER PRIMARY KEY,topic_id INTEGER NOT NULL,"
    "timestamp INTEGER NOT NULL, data BLOB NOT NULL);"
    "CREATE INDEX timestamp_idx ON messages (timestamp ASC);";

class SqliteStorageWriter final : public StorageWriter {
 public:
  explicit SqliteStorageWriter(const std::string& path)
      : db_(path, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE | SQLITE_OPEN_NOMUTEX) {
    db_.Exec("PRAGMA page_size=4096");
    db_.Exec(kHumbleSchema);
    db_.Exec("BEGIN");
    insert_topic_ = std::make_unique<SqliteStatement>(
        db_,
        "INSERT INTO topics(id,name,type,serialization_format,offered_qos_profiles) "
        "VALUES(?,?,?,?,?)");
    insert_message_ = std::make_unique<SqliteStatement>(
        db_, "INSERT INTO messages(topic_id,timestamp,data) VALUES(?,?,?)");
  }

  void AddTopic(const TopicInfo& topic) override {
    ++num_topics_;
    insert_topic_->Reset();
    insert_topic_->Bind(1, static_cast<std::int64_t>(num_topics_));
    insert_topic_->Bind(2, topic.name);
    insert_topic_->Bind(3, topic.type);
    insert_topic_->Bind(4, topic.serialization_format);
    insert_topic_->Bind(5, topic.offered_qos_profiles);
    insert_topic_->Step();
  }

  void Write(int topic, TimestampNs log_time_ns, const std::uint8_t* data,
             std::size_t size) override {
    insert_message_->Reset();
    insert_message_->Bind(1, static_cast<std::int64_t>(topic + 1));
    insert_message_->Bind(2, log_time_ns);
    insert_message_->BindBlob(3, size > 0 ? data : reinterpret_cast<const std::uint8_t*>(""), size);
    insert_message_->Step();
  }

  void Flush() override {
    db_.Exec("COMMIT");
    db_.Exec("BEGIN");
  }

  void Close(const std::string& metadata_yaml) override {
    SqliteStatement q(db_, "INSERT INTO metadata(metadata_version,metadata) VALUES(5,?)");
    q.Bind(1, metadata_yaml);
    q.Step();
    insert_topic_.reset();
    insert_message_.reset();
    db_.Exec("COMMIT");
  }

 private:
  SqliteDb db_;
  int num_topics_ = 0;
  std::unique_ptr<SqliteStatement> insert_topic_;
  std::unique_ptr<SqliteStatement> insert_message_;
};

}  // namespace

std::unique_ptr<StorageWriter> CreateSqliteStorage(const std::string& path) {
  return std::make_unique<SqliteStorageWriter>(path);
}

}  // namespace uwbsar::rosbag
