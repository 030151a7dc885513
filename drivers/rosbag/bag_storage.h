// The storage layer of a rosbag2 bag: one file (.db3 or .mcap) read or written
// message by message. BagReader/BagWriter put files together into a bag; the two
// implementations (sqlite_storage_*.cc, mcap_storage_*.cc) know one format each.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/types.h"

namespace uwbsar::rosbag {

/// One topic (an MCAP channel, a row of the sqlite `topics` table).
struct TopicInfo {
  std::string name;
  std::string type;                          ///< e.g. "nav_msgs/msg/Odometry"
  std::string serialization_format = "cdr";  ///< MCAP message_encoding
  std::string offered_qos_profiles;          ///< YAML text as stored (may be empty)
  std::string type_description_hash;         ///< RIHS01_... (Iron and later), may be empty
  std::string message_definition;            ///< schema text (MCAP / sqlite schema 4), may be empty
  std::string definition_encoding;           ///< "ros2msg", "ros2idl" or empty
  std::uint64_t message_count = 0;
};

/// One message as stored. `data` points into the reader's buffers and stays valid
/// until the next call to Next() on the same reader.
struct StorageMessage {
  int topic = -1;               ///< index into the reader's Topics()
  TimestampNs log_time_ns = 0;  ///< receive time (rosbag2 "timestamp", MCAP log_time)
  const std::uint8_t* data = nullptr;
  std::size_t size = 0;
};

/// Counts and time range of one storage file.
struct StorageStats {
  std::uint64_t message_count = 0;
  TimestampNs start_ns = 0;  ///< earliest log time (0 when empty)
  TimestampNs end_ns = 0;    ///< latest log time (0 when empty)
};

class StorageReader {
 public:
  virtual ~StorageReader() = default;
  virtual const std::string& Path() const = 0;
  virtual const char* StorageId() const = 0;  ///< "sqlite3" or "mcap"
  /// Topics; their message counts are filled once Stats() has been called (sqlite
  /// counts with a query, which a bag with metadata.yaml does not need).
  virtual const std::vector<TopicInfo>& Topics() = 0;
  /// Counts and time range of this file.
  virtual StorageStats Stats() = 0;
  /// The next message in log-time order (ties in file order); false at the end.
  /// Throws InputError naming the file and what is wrong on corrupt data.
  virtual bool Next(StorageMessage* msg) = 0;
};

class StorageWriter {
 public:
  virtual ~StorageWriter() = default;
  /// Registers a topic; topics are numbered 0, 1, ... in the order added.
  virtual void AddTopic(const TopicInfo& topic) = 0;
  virtual void Write(int topic, TimestampNs log_time_ns, const std::uint8_t* data,
                     std::size_t size) = 0;
  /// Makes everything written so far durable in the file (a reader sees it).
  virtual void Flush() = 0;
  /// Finishes the file; `metadata_yaml` (the bag's metadata) is stored inside it too,
  /// as rosbag2 does, so `ros2 bag reindex` can recover it.
  virtual void Close(const std::string& metadata_yaml) = 0;
};

/// How damaged storage is read.
struct BagReadOptions {
  /// MCAP: a chunk that fails its CRC or cannot be decompressed is skipped with a warning
  /// naming its offset and message count, instead of failing the whole read.
  bool skip_damaged_chunks = false;
};

std::unique_ptr<StorageReader> OpenSqliteStorage(const std::string& path);
std::unique_ptr<StorageReader> OpenMcapStorage(const std::string& path,
                                               const BagReadOptions& options = {});

struct McapWriteOptions {
  std::string compression = "zstd";         ///< chunk compression: "", "zstd" or "lz4"
  std::size_t chunk_size_bytes = 1u << 20;  ///< a chunk is closed when it holds this much
};

std::unique_ptr<StorageWriter> CreateSqliteStorage(const std::string& path);
std::unique_ptr<StorageWriter> CreateMcapStorage(const std::string& path,
                                                 const McapWriteOptions& options);

}  // namespace uwbsar::rosbag
