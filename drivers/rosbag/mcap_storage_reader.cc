#include "drivers/rosbag/mcap_storage_reader.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <limits>
#include <map>
#include <queue>

#include "drivers/rosbag/crc32.h"
#include "drivers/rosbag/mcap_format.h"
#include "slam/errors.h"

namespace uwbsar::rosbag {
namespace {

using mcap::Cursor;

// A time-sorted source of messages: one chunk, or a run of loose message records
// whose log times do not decrease.
struct Segment {
  bool is_chunk = false;
  std::uint64_t offset = 0;  // first record
  std::uint64_t end = 0;     // one past the last record
  TimestampNs start_ns = 0;
  TimestampNs end_ns = 0;
};

struct Entry {
  TimestampNs log_time_ns = 0;
  int topic = -1;
  std::size_t offset = 0;  // of the payload in the iterator's buffer
  std::size_t size = 0;
};

struct SegmentIterator {
  bool is_chunk = false;
  int order = 0;                     // segment index: ties in log time go in file order
  std::vector<std::uint8_t> buffer;  // decompressed chunk, or the current loose record
  std::vector<Entry> entries;        // chunk: sorted messages
  std::size_t next = 0;              // chunk: index of the head entry
  std::uint64_t pos = 0, end = 0;    // loose run: file range still to read
  Entry head;
};

struct HeadLater {
  bool operator()(const SegmentIterator* a, const SegmentIterator* b) const {
    if (a->head.log_time_ns != b->head.log_time_ns)
      return a->head.log_time_ns > b->head.log_time_ns;
    return a->order > b->order;
  }
};

TimestampNs ToNs(std::uint64_t t, const Cursor& c) {
  if (t > static_cast<std::uint64_t>(std::numeric_limits<TimestampNs>::max())) {
    c.Fail("time " + std::to_string(t) + " ns is out of range");
  }
  return static_cast<TimestampNs>(t);
}

class McapStorageReader final : public StorageReader {
 public:
  explicit McapStorageReader(std::unique_ptr<ByteSource> source) : src_(std::move(source)) {
    Open();
  }
  ~McapStorageReader() override {
    while (!heap_.empty()) {
      delete heap_.top();
      heap_.pop();
    }
    delete pending_;
  }

  const std::string& Path() const override { return src_->Name(); }
  const char* StorageId() const override { return "mcap"; }
  const std::vector<TopicInfo>& Topics() override { return topics_; }
  StorageStats Stats() override { return stats_; }

  bool Next(StorageMessage* msg) override {
    reading_ = true;
    if (pending_) {
      if (Advance(pending_)) {
        heap_.push(pending_);
      } else {
        delete pending_;
      }
      pending_ = nullptr;
    }
    // Open every segment that may hold a message before the current earliest head.
    while (next_segment_ < segments_.size() &&
           (heap_.empty() || segments_[next_segment_].start_ns <= heap_.top()->head.log_time_ns)) {
      auto* it = new SegmentIterator;
      it->order = static_cast<int>(next_segment_);
      const Segment& s = segments_[next_segment_++];
      bool has_head = false;
      try {
        if (s.is_chunk) {
          LoadChunk(s, it);
        } else {
          it->pos = s.offset;
          it->end = s.end;
        }
        has_head = Advance(it);
      } catch (...) {
        delete it;
        throw;
      }
      if (has_head) {
        heap_.push(it);
      } else {
        delete it;
      }
    }
    if (heap_.empty()) return false;
    pending_ = heap_.top();
    heap_.pop();
    // The merge is only as good as the file's time ranges: a segment whose messages start
    // before its declared start would come out late. Refuse rather than mis-order.
    if (pending_->head.log_time_ns < last_log_time_ns_) {
      Fail("message at log time " + std::to_string(pending_->head.log_time_ns) +
           " ns follows one at " + std::to_string(last_log_time_ns_) +
           " ns: the file's chunk time ranges are inconsistent");
    }
    last_log_time_ns_ = pending_->head.log_time_ns;
    msg->topic = pending_->head.topic;
    msg->log_time_ns = pending_->head.log_time_ns;
    msg->data = pending_->buffer.data() + pending_->head.offset;
    msg->size = pending_->head.size;
    return true;
  }

 private:
  [[noreturn]] void Fail(const std::string& what) const { throw InputError(Path() + ": " + what); }

  std::vector<std::uint8_t> ReadBytes(std::uint64_t offset, std::uint64_t size) const {
    if (offset > src_->Size() || size > src_->Size() - offset) {
      Fail("truncated or corrupt: " + std::to_string(size) + " bytes at offset " +
           std::to_string(offset) + " lie beyond the end of the " + std::to_string(src_->Size()) +
           "-byte file");
    }
    std::vector<std::uint8_t> out(static_cast<std::size_t>(size));
    src_->ReadAt(offset, out.size(), out.data());
    return out;
  }

  // Reads the 9-byte header of the record at `offset`, checking it ends by `limit`.
  std::pair<std::uint8_t, std::uint64_t> RecordHeader(std::uint64_t offset,
                                                      std::uint64_t limit) const {
    if (offset + mcap::kRecordHeaderBytes > limit) {
      Fail("truncated or corrupt: record header at offset " + std::to_string(offset) +
           " runs past the end of its section at " + std::to_string(limit));
    }
    std::uint8_t h[mcap::kRecordHeaderBytes];
    src_->ReadAt(offset, sizeof(h), h);
    std::uint64_t length = 0;
    std::memcpy(&length, h + 1, 8);
    if (length > limit - offset - mcap::kRecordHeaderBytes) {
      Fail("truncated or corrupt: " + mcap::OpcodeName(h[0]) + " record at offset " +
           std::to_string(offset) + " claims " + std::to_string(length) +
           " bytes, past the end of its section at " + std::to_string(limit));
    }
    return {h[0], length};
  }

  void Open() {
    const std::uint64_t size = src_->Size();
    const std::uint64_t min_size =
        2 * sizeof(mcap::kMagic) + mcap::kRecordHeaderBytes + mcap::kFooterContentBytes;
    std::uint8_t magic[8] = {};
    src_->ReadAt(0, std::min<std::uint64_t>(size, 8), magic);
    if (size < 8 || std::memcmp(magic, mcap::kMagic, 8) != 0) {
      Fail("bad magic: not an MCAP file (expected 89 4D 43 41 50 30 0D 0A)");
    }
    if (size < min_size) Fail("truncated: " + std::to_string(size) + " bytes is too short");
    src_->ReadAt(size - 8, 8, magic);
    if (std::memcmp(magic, mcap::kMagic, 8) != 0) {
      Fail("truncated or corrupt: no MCAP magic at the end of the file (recording cut short?)");
    }
    const std::uint64_t footer_at = size - 8 - mcap::kRecordHeaderBytes - mcap::kFooterContentBytes;
    const auto footer = ReadBytes(footer_at, mcap::kRecordHeaderBytes + mcap::kFooterContentBytes);
    std::uint64_t footer_length = 0;
    std::memcpy(&footer_length, footer.data() + 1, 8);
    if (footer[0] != mcap::kFooter || footer_length != mcap::kFooterContentBytes) {
      Fail("corrupt: no Footer record before the closing magic");
    }
    Cursor fc(footer.data() + mcap::kRecordHeaderBytes, mcap::kFooterContentBytes, Path(),
              footer_at, mcap::kFooter);
    const std::uint64_t summary_start = fc.U64();
    const std::uint64_t summary_offset_start = fc.U64();
    const std::uint32_t summary_crc = fc.U32();
    std::uint64_t data_end = footer_at;
    bool summary_complete = false;
    if (summary_start != 0) {
      if (summary_start < 8 || summary_start > footer_at) {
        Fail("corrupt Footer: summary_start " + std::to_string(summary_start) +
             " is outside the file");
      }
      data_end = summary_start;
      if (summary_crc != 0) {
        const auto bytes = ReadBytes(summary_start, footer_at + 1 + 8 + 16 - summary_start);
        const std::uint32_t crc = Crc32(0, bytes.data(), bytes.size());
        if (crc != summary_crc) {
          Fail("summary CRC mismatch: Footer says " + Hex(summary_crc) + ", the bytes give " +
               Hex(crc));
        }
      }
      const std::uint64_t summary_end =
          (summary_offset_start >= summary_start && summary_offset_start <= footer_at &&
           summary_offset_start != 0)
              ? summary_offset_start
              : footer_at;
      summary_complete = ReadSummary(summary_start, summary_end);
    }
    ScanDataSection(data_end, !summary_complete);
    std::stable_sort(segments_.begin(), segments_.end(),
                     [](const Segment& a, const Segment& b) { return a.start_ns < b.start_ns; });
  }

  static std::string Hex(std::uint32_t v) {
    char buf[16];
    std::snprintf(buf, sizeof(buf), "0x%08x", v);
    return buf;
  }

  // Returns true when the summary has channels and statistics, so that no chunk needs
  // to be opened before iteration.
  bool ReadSummary(std::uint64_t begin, std::uint64_t end) {
    bool have_stats = false;
    std::map<std::uint16_t, std::uint64_t> counts;
    for (std::uint64_t off = begin; off < end;) {
      const auto [op, length] = RecordHeader(off, end);
      const std::uint64_t content = off + mcap::kRecordHeaderBytes;
      if (op == mcap::kSchema || op == mcap::kChannel || op == mcap::kStatistics) {
        const auto bytes = ReadBytes(content, length);
        Cursor c(bytes.data(), bytes.size(), Path(), off, op);
        if (op == mcap::kSchema) AddSchema(c);
        if (op == mcap::kChannel) AddChannel(c);
        if (op == mcap::kStatistics) {
          stats_.message_count = c.U64();
          c.U16();  // schema_count
          c.U32();  // channel_count
          c.U32();  // attachment_count
          c.U32();  // metadata_count
          c.U32();  // chunk_count
          stats_.start_ns = ToNs(c.U64(), c);
          stats_.end_ns = ToNs(c.U64(), c);
          for (const auto& [id, n] : c.U16U64Map()) counts[id] = n;
          have_stats = true;
        }
      }
      off = content + length;
    }
    if (!have_stats || channels_.empty()) {
      stats_ = {};
      return false;
    }
    for (const auto& [id, n] : counts) {
      const auto it = channels_.find(id);
      if (it != channels_.end()) topics_[static_cast<std::size_t>(it->second)].message_count = n;
    }
    return true;
  }

  void AddSchema(Cursor& c) {
    const std::uint16_t id = c.U16();
    if (id == 0) c.Fail("schema id 0 is reserved");
    SchemaInfo s;
    s.name = c.String();
    s.encoding = c.String();
    const auto [data, n] = c.Bytes32();
    s.data.assign(reinterpret_cast<const char*>(data), n);
    schemas_.emplace(id, std::move(s));
  }

  void AddChannel(Cursor& c) {
    const std::uint16_t id = c.U16();
    const std::uint16_t schema_id = c.U16();
    TopicInfo t;
    t.name = c.String();
    t.serialization_format = c.String();
    for (auto& [key, value] : c.StringMap()) {
      if (key == "offered_qos_profiles") t.offered_qos_profiles = std::move(value);
      if (key == "topic_type_hash") t.type_description_hash = std::move(value);
    }
    if (schema_id != 0) {
      const auto s = schemas_.find(schema_id);
      if (s == schemas_.end()) {
        c.Fail("channel " + std::to_string(id) + " (" + t.name + ") refers to schema " +
               std::to_string(schema_id) + " which has not been defined");
      }
      t.type = s->second.name;
      t.message_definition = s->second.data;
      t.definition_encoding = s->second.encoding;
    }
    if (channels_.count(id)) return;  // repeated in chunks and summary
    // Readers list the topics once, when the file is opened: a channel that only shows up
    // while messages are being read (in a chunk the summary does not account for) cannot
    // be given to them.
    if (reading_) {
      c.Fail("channel " + std::to_string(id) + " (" + t.name +
             ") appears in a chunk but not in the summary");
    }
    channels_[id] = static_cast<int>(topics_.size());
    topics_.push_back(std::move(t));
  }

  int TopicOf(std::uint16_t channel, const Cursor& c) const {
    const auto it = channels_.find(channel);
    if (it == channels_.end()) {
      c.Fail("message on channel " + std::to_string(channel) + " which has not been defined");
    }
    return it->second;
  }

  void Count(int topic, TimestampNs t) {
    topics_[static_cast<std::size_t>(topic)].message_count++;
    stats_.start_ns = stats_.message_count == 0 ? t : std::min(stats_.start_ns, t);
    stats_.end_ns = stats_.message_count == 0 ? t : std::max(stats_.end_ns, t);
    stats_.message_count++;
  }

  void ScanDataSection(std::uint64_t end, bool count) {
    bool first = true;
    Segment run;
    bool in_run = false;
    std::vector<std::uint8_t> chunk;
    for (std::uint64_t off = 8; off < end;) {
      const auto [op, length] = RecordHeader(off, end);
      const std::uint64_t content = off + mcap::kRecordHeaderBytes;
      const std::uint64_t next = content + length;
      if (first && op != mcap::kHeader) {
        Fail("corrupt: the first record is " + mcap::OpcodeName(op) + ", not Header");
      }
      first = false;
      if (op == mcap::kDataEnd || op == mcap::kFooter) break;
      if (op == mcap::kSchema || op == mcap::kChannel) {
        const auto bytes = ReadBytes(content, length);
        Cursor c(bytes.data(), bytes.size(), Path(), off, op);
        op == mcap::kSchema ? AddSchema(c) : AddChannel(c);
      } else if (op == mcap::kMessage) {
        const auto bytes = ReadBytes(content, std::min<std::uint64_t>(length, 14));
        Cursor c(bytes.data(), bytes.size(), Path(), off, op);
        const std::uint16_t channel = c.U16();
        c.U32();
        const TimestampNs t = ToNs(c.U64(), c);
        const int topic = TopicOf(channel, c);
        if (count) Count(topic, t);
        if (in_run && t < run.end_ns) {
          segments_.push_back(run);
          in_run = false;
        }
        if (!in_run) run = Segment{false, off, next, t, t};
        in_run = true;
        run.end = next;
        run.end_ns = t;
      } else if (op == mcap::kChunk) {
        if (in_run) segments_.push_back(run);
        in_run = false;
        const auto bytes = ReadBytes(content, std::min<std::uint64_t>(length, 16));
        Cursor c(bytes.data(), bytes.size(), Path(), off, op);
        Segment s{true, off, next, 0, 0};
        s.start_ns = ToNs(c.U64(), c);
        s.end_ns = ToNs(c.U64(), c);
        segments_.push_back(s);
        if (count) {
          SegmentIterator it;
          LoadChunk(s, &it);
          for (const Entry& e : it.entries) Count(e.topic, e.log_time_ns);
        }
      }
      off = next;
    }
    if (first) Fail("corrupt: no Header record after the magic");
    if (in_run) segments_.push_back(run);
  }

  // Decompresses and CRC-checks a chunk, registers the schemas and channels inside it
  // and lists its messages sorted by log time.
  void LoadChunk(const Segment& s, SegmentIterator* it) {
    it->is_chunk = true;
    const auto raw =
        ReadBytes(s.offset + mcap::kRecordHeaderBytes, s.end - s.offset - mcap::kRecordHeaderBytes);
    Cursor c(raw.data(), raw.size(), Path(), s.offset, mcap::kChunk);
    c.U64();
    c.U64();
    const std::uint64_t uncompressed_size = c.U64();
    const std::uint32_t crc = c.U32();
    const std::string compression = c.String();
    const auto [data, n] = c.Bytes64();
    const std::string context =
        Path() + ": MCAP Chunk record at offset " + std::to_string(s.offset);
    mcap::Decompress(compression, data, n, uncompressed_size, context, &it->buffer);
    if (crc != 0) {
      const std::uint32_t actual = Crc32(0, it->buffer.data(), it->buffer.size());
      if (actual != crc) {
        Fail("chunk CRC mismatch in the Chunk record at offset " + std::to_string(s.offset) +
             ": record says " + Hex(crc) + ", the data gives " + Hex(actual));
      }
    }
    const std::vector<std::uint8_t>& b = it->buffer;
    it->entries.clear();
    for (std::size_t off = 0; off < b.size();) {
      if (b.size() - off < mcap::kRecordHeaderBytes) c.Fail("truncated record inside the chunk");
      const std::uint8_t op = b[off];
      std::uint64_t length = 0;
      std::memcpy(&length, b.data() + off + 1, 8);
      const std::size_t content = off + mcap::kRecordHeaderBytes;
      if (length > b.size() - content) {
        c.Fail(mcap::OpcodeName(op) + " record at chunk offset " + std::to_string(off) +
               " runs past the end of the chunk");
      }
      Cursor r(b.data() + content, static_cast<std::size_t>(length), Path(), s.offset, op);
      if (op == mcap::kSchema) AddSchema(r);
      if (op == mcap::kChannel) AddChannel(r);
      if (op == mcap::kChunk) c.Fail("nested Chunk record");
      if (op == mcap::kMessage) {
        const std::uint16_t channel = r.U16();
        r.U32();
        Entry e;
        e.log_time_ns = ToNs(r.U64(), r);
        r.U64();
        // The merge opens chunks by their declared start time, so a message before it
        // would come out of order: the spec makes the range binding, so hold it to it.
        if (e.log_time_ns < s.start_ns || e.log_time_ns > s.end_ns) {
          r.Fail("message log_time " + std::to_string(e.log_time_ns) +
                 " lies outside the chunk's declared range [" + std::to_string(s.start_ns) + ", " +
                 std::to_string(s.end_ns) + "]");
        }
        e.topic = TopicOf(channel, r);
        e.offset = content + 22;
        e.size = static_cast<std::size_t>(length) - 22;
        it->entries.push_back(e);
      }
      off = content + static_cast<std::size_t>(length);
    }
    std::stable_sort(it->entries.begin(), it->entries.end(),
                     [](const Entry& a, const Entry& b) { return a.log_time_ns < b.log_time_ns; });
    it->next = 0;
  }

  // Moves the iterator to its next message; false when it has none.
  bool Advance(SegmentIterator* it) {
    if (it->is_chunk) {
      if (it->next >= it->entries.size()) return false;
      it->head = it->entries[it->next++];
      return true;
    }
    while (it->pos < it->end) {
      const auto [op, length] = RecordHeader(it->pos, it->end);
      const std::uint64_t at = it->pos;
      it->pos += mcap::kRecordHeaderBytes + length;
      if (op != mcap::kMessage) continue;
      it->buffer = ReadBytes(at + mcap::kRecordHeaderBytes, length);
      Cursor c(it->buffer.data(), it->buffer.size(), Path(), at, op);
      const std::uint16_t channel = c.U16();
      c.U32();
      it->head.log_time_ns = ToNs(c.U64(), c);
      c.U64();
      it->head.topic = TopicOf(channel, c);
      it->head.offset = 22;
      it->head.size = it->buffer.size() - 22;
      return true;
    }
    return false;
  }

  struct SchemaInfo {
    std::string name, encoding, data;
  };

  std::unique_ptr<ByteSource> src_;
  std::map<std::uint16_t, SchemaInfo> schemas_;
  std::map<std::uint16_t, int> channels_;
  std::vector<TopicInfo> topics_;
  StorageStats stats_;
  std::vector<Segment> segments_;
  std::size_t next_segment_ = 0;
  TimestampNs last_log_time_ns_ = std::numeric_limits<TimestampNs>::min();
  bool reading_ = false;  // Next() has been called: the topic list is final
  std::priority_queue<SegmentIterator*, std::vector<SegmentIterator*>, HeadLater> heap_;
  SegmentIterator* pending_ = nullptr;
};

}  // namespace

std::unique_ptr<StorageReader> OpenMcapStorage(std::unique_ptr<ByteSource> source) {
  return std::make_unique<McapStorageReader>(std::move(source));
}

std::unique_ptr<StorageReader> OpenMcapStorage(const std::string& path) {
  return OpenMcapStorage(OpenFileSource(path));
}

}  // namespace uwbsar::rosbag
