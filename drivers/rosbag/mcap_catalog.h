// What the MCAP reader knows about one file before it hands out messages: schemas,
// channels (as topics), statistics and the list of time-sorted segments (chunks and
// runs of loose messages) to merge. Filled either from the summary section
// (mcap_summary.h) or by walking the data section (mcap_data_scan.h); this class holds
// the record-level helpers both share, and decodes a Chunk into its messages.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "drivers/rosbag/bag_storage.h"
#include "drivers/rosbag/byte_source.h"
#include "drivers/rosbag/mcap_format.h"

namespace uwbsar::rosbag::mcap {

/// A time-sorted source of messages: one chunk, or a run of loose message records
/// whose log times do not decrease.
struct Segment {
  bool is_chunk = false;
  std::uint64_t offset = 0;  ///< first record
  std::uint64_t end = 0;     ///< one past the last record
  TimestampNs start_ns = 0;
  TimestampNs end_ns = 0;
};

/// One message of a decoded chunk (or the current loose record).
struct Entry {
  TimestampNs log_time_ns = 0;
  int topic = -1;
  std::size_t offset = 0;  ///< of the payload in the owner's buffer
  std::size_t size = 0;
};

/// A decompressed, CRC-checked chunk and its messages sorted by log time.
struct ChunkMessages {
  std::vector<std::uint8_t> buffer;
  std::vector<Entry> entries;
};

/// The bytes of a Message record's content before the payload.
inline constexpr std::size_t kMessageHeaderBytes = 22;

class Catalog {
 public:
  explicit Catalog(const ByteSource& src) : src_(&src) {}

  const std::string& Path() const { return src_->Name(); }
  const ByteSource& Source() const { return *src_; }
  [[noreturn]] void Fail(const std::string& what) const;

  /// `size` bytes at `offset`; throws InputError("truncated or corrupt...") past the end.
  std::vector<std::uint8_t> ReadBytes(std::uint64_t offset, std::uint64_t size) const;
  /// Opcode and content length of the record at `offset`, checked to end by `limit`.
  std::pair<std::uint8_t, std::uint64_t> RecordHeader(std::uint64_t offset,
                                                      std::uint64_t limit) const;

  void AddSchema(Cursor& c);
  void AddChannel(Cursor& c);
  /// Topic index of a channel; the cursor names the record when it is undefined.
  int TopicOf(std::uint16_t channel, const Cursor& c) const;
  /// Counts one message into the topic counts and the statistics.
  void Count(int topic, TimestampNs t);
  /// Sets the per-channel counts read from a Statistics record.
  void SetChannelCounts(const std::map<std::uint16_t, std::uint64_t>& counts);
  /// Forgets counts and statistics (the summary's were incomplete: recount by scanning).
  void ResetCounts();
  /// After this, a channel that appears for the first time (inside a chunk read while
  /// merging) is an error: readers were given the topic list already.
  void FreezeTopics() { frozen_ = true; }

  /// Decompresses and CRC-checks the chunk of `s`, registers the schemas and channels in
  /// it and lists its messages sorted by log time. Throws InputError on any damage.
  void LoadChunk(const Segment& s, ChunkMessages* out);
  /// LoadChunk; with skip_damaged_chunks a damaged chunk is logged (offset, message count
  /// from its MessageIndex records, the damage) and skipped: false, `out` empty.
  bool LoadChunkOrSkip(const Segment& s, ChunkMessages* out);
  /// Messages listed by the MessageIndex records that follow the chunk of `s`; -1 if none.
  long long IndexedMessages(const Segment& s) const;

  bool skip_damaged_chunks = false;  ///< BagReadOptions::skip_damaged_chunks
  std::uint64_t skipped_chunks = 0;  ///< chunks skipped so far

  std::vector<TopicInfo> topics;
  StorageStats stats;
  std::vector<Segment> segments;

 private:
  struct SchemaInfo {
    std::string name, encoding, data;
  };

  const ByteSource* src_;  // not owned
  std::map<std::uint16_t, SchemaInfo> schemas_;
  std::map<std::uint16_t, int> channels_;
  bool frozen_ = false;
};

/// Nanoseconds as TimestampNs; the cursor names the record when out of range.
TimestampNs ToNs(std::uint64_t t, const Cursor& c);
/// "0x1234abcd".
std::string Hex(std::uint32_t v);

}  // namespace uwbsar::rosbag::mcap
