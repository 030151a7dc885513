// Reading a ROS 2 bag without ROS: a bag directory (metadata.yaml + one or more
// .db3/.mcap files, optionally zstd-compressed per file or per message) or a bare
// .db3/.mcap file. Messages come out in receive-time order across all files (a
// k-way merge over streaming file readers: memory stays at one message per file
// plus the MCAP chunks in flight).
#pragma once

#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "drivers/rosbag/bag_storage.h"

namespace uwbsar::rosbag {

/// What `ros2 bag info` shows.
struct BagInfo {
  std::string path;                ///< as opened
  std::string storage_identifier;  ///< "sqlite3" or "mcap"
  int metadata_version = 0;        ///< 0 for a bare file
  std::string ros_distro;
  std::vector<std::string> files;  ///< storage files, in the bag's order
  std::uint64_t size_bytes = 0;    ///< of the storage files
  std::string compression_format, compression_mode;
  std::vector<TopicInfo> topics;  ///< with counts, definitions where stored
  std::uint64_t message_count = 0;
  TimestampNs start_ns = 0;
  TimestampNs end_ns = 0;
  /// end - start, saturated instead of overflowing (a damaged file's stamps can be anything).
  std::int64_t duration_ns() const {
    std::int64_t d = 0;
    if (__builtin_sub_overflow(end_ns, start_ns, &d)) return std::numeric_limits<int64_t>::max();
    return d;
  }
};

/// One message. `data` is valid until the next call to BagReader::Next().
struct BagMessage {
  int topic = -1;  ///< index into BagInfo::topics
  int file = -1;   ///< index into BagInfo::files (for messages naming the file)
  TimestampNs log_time_ns = 0;
  const std::uint8_t* data = nullptr;
  std::size_t size = 0;
};

class BagReader {
 public:
  /// Opens a bag directory or a bare .db3/.mcap file. Throws InputError naming the
  /// file and what is wrong (missing metadata, unknown storage id, bad magic, ...).
  explicit BagReader(const std::string& path, const BagReadOptions& options = {});
  ~BagReader();
  BagReader(const BagReader&) = delete;
  BagReader& operator=(const BagReader&) = delete;

  const BagInfo& Info() const { return info_; }
  /// Index of the topic named `name` in Info().topics, -1 if absent.
  int FindTopic(const std::string& name) const;
  /// The next message in receive-time order (ties: file order); false at the end.
  bool Next(BagMessage* msg);

 private:
  struct File;
  void OpenDirectory(const std::string& dir);
  void OpenBareFile(const std::string& path);
  int MergeTopic(const TopicInfo& t);
  bool Advance(std::size_t file);

  BagInfo info_;
  BagReadOptions options_;
  bool message_compression_ = false;
  std::vector<std::unique_ptr<File>> files_;
  std::vector<std::size_t> heap_;  // files with a current message, min-heap by time
  long last_ = -1;                 // file whose message was returned last
  std::vector<std::uint8_t> decompressed_;
};

/// The most bytes a file-compressed (zstd FILE mode) storage file holding `message_count`
/// messages may decompress to: 64 MiB + 1 MiB per message, at most 1 TiB.
std::uint64_t DecompressedSizeCap(std::uint64_t message_count);

/// "sqlite3" or "mcap" from a file's first bytes; empty when neither.
std::string DetectStorage(const std::string& path);

}  // namespace uwbsar::rosbag
