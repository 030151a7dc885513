#include "drivers/rosbag/mcap_catalog.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <limits>

#include "core/errors.h"
#include "core/log.h"
#include "drivers/rosbag/crc32.h"

namespace uwbsar::rosbag::mcap {

TimestampNs ToNs(std::uint64_t t, const Cursor& c) {
  if (t > static_cast<std::uint64_t>(std::numeric_limits<TimestampNs>::max())) {
    c.Fail("time " + std::to_string(t) + " ns is out of range");
  }
  return static_cast<TimestampNs>(t);
}

std::string Hex(std::uint32_t v) {
  char buf[16];
  std::snprintf(buf, sizeof(buf), "0x%08x", v);
  return buf;
}

void Catalog::Fail(const std::string& what) const { throw InputError(Path() + ": " + what); }

std::vector<std::uint8_t> Catalog::ReadBytes(std::uint64_t offset, std::uint64_t size) const {
  if (offset > src_->Size() || size > src_->Size() - offset) {
    Fail("truncated or corrupt: " + std::to_string(size) + " bytes at offset " +
         std::to_string(offset) + " lie beyond the end of the " + std::to_string(src_->Size()) +
         "-byte file");
  }
  std::vector<std::uint8_t> out(static_cast<std::size_t>(size));
  src_->ReadAt(offset, out.size(), out.data());
  return out;
}

std::pair<std::uint8_t, std::uint64_t> Catalog::RecordHeader(std::uint64_t offset,
                                                             std::uint64_t limit) const {
  if (offset > limit || limit - offset < kRecordHeaderBytes) {
    Fail("truncated or corrupt: record header at offset " + std::to_string(offset) +
         " runs past the end of its section at " + std::to_string(limit));
  }
  std::uint8_t h[kRecordHeaderBytes];
  src_->ReadAt(offset, sizeof(h), h);
  std::uint64_t length = 0;
  std::memcpy(&length, h + 1, 8);
  if (length > limit - offset - kRecordHeaderBytes) {
    Fail("truncated or corrupt: " + OpcodeName(h[0]) + " record at offset " +
         std::to_string(offset) + " claims " + std::to_string(length) +
         " bytes, past the end of its section at " + std::to_string(limit));
  }
  return {h[0], length};
}

void Catalog::AddSchema(Cursor& c) {
  const std::uint16_t id = c.U16();
  if (id == 0) c.Fail("schema id 0 is reserved");
  SchemaInfo s;
  s.name = c.String();
  s.encoding = c.String();
  const auto [data, n] = c.Bytes32();
  s.data.assign(reinterpret_cast<const char*>(data), n);
  schemas_.emplace(id, std::move(s));
}

void Catalog::AddChannel(Cursor& c) {
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
  if (frozen_) {
    c.Fail("channel " + std::to_string(id) + " (" + t.name +
           ") appears in a chunk but not in the summary");
  }
  channels_[id] = static_cast<int>(topics.size());
  topics.push_back(std::move(t));
}

int Catalog::TopicOf(std::uint16_t channel, const Cursor& c) const {
  const auto it = channels_.find(channel);
  if (it == channels_.end()) {
    c.Fail("message on channel " + std::to_string(channel) + " which has not been defined");
  }
  return it->second;
}

void Catalog::Count(int topic, TimestampNs t) {
  topics[static_cast<std::size_t>(topic)].message_count++;
  stats.start_ns = stats.message_count == 0 ? t : std::min(stats.start_ns, t);
  stats.end_ns = stats.message_count == 0 ? t : std::max(stats.end_ns, t);
  stats.message_count++;
}

void Catalog::SetChannelCounts(const std::map<std::uint16_t, std::uint64_t>& counts) {
  for (const auto& [id, n] : counts) {
    const auto it = channels_.find(id);
    if (it != channels_.end()) topics[static_cast<std::size_t>(it->second)].message_count = n;
  }
}

void Catalog::ResetCounts() {
  stats = {};
  for (TopicInfo& t : topics) t.message_count = 0;
}

void Catalog::LoadChunk(const Segment& s, ChunkMessages* out) {
  const auto raw = ReadBytes(s.offset + kRecordHeaderBytes, s.end - s.offset - kRecordHeaderBytes);
  Cursor c(raw.data(), raw.size(), Path(), s.offset, kChunk);
  c.U64();
  c.U64();
  const std::uint64_t uncompressed_size = c.U64();
  const std::uint32_t crc = c.U32();
  const std::string compression = c.String();
  const auto [data, n] = c.Bytes64();
  const std::string context = Path() + ": MCAP Chunk record at offset " + std::to_string(s.offset);
  Decompress(compression, data, n, uncompressed_size, context, &out->buffer);
  if (crc != 0) {
    const std::uint32_t actual = Crc32(0, out->buffer.data(), out->buffer.size());
    if (actual != crc) {
      Fail("chunk CRC mismatch in the Chunk record at offset " + std::to_string(s.offset) +
           ": record says " + Hex(crc) + ", the data gives " + Hex(actual));
    }
  }
  const std::vector<std::uint8_t>& b = out->buffer;
  out->entries.clear();
  for (std::size_t off = 0; off < b.size();) {
    if (b.size() - off < kRecordHeaderBytes) c.Fail("truncated record inside the chunk");
    const std::uint8_t op = b[off];
    std::uint64_t length = 0;
    std::memcpy(&length, b.data() + off + 1, 8);
    const std::size_t content = off + kRecordHeaderBytes;
    if (length > b.size() - content) {
      c.Fail(OpcodeName(op) + " record at chunk offset " + std::to_string(off) +
             " runs past the end of the chunk");
    }
    Cursor r(b.data() + content, static_cast<std::size_t>(length), Path(), s.offset, op);
    if (op == kSchema) AddSchema(r);
    if (op == kChannel) AddChannel(r);
    if (op == kChunk) c.Fail("nested Chunk record");
    if (op == kMessage) {
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
      e.offset = content + kMessageHeaderBytes;
      e.size = static_cast<std::size_t>(length) - kMessageHeaderBytes;
      out->entries.push_back(e);
    }
    off = content + static_cast<std::size_t>(length);
  }
  std::stable_sort(out->entries.begin(), out->entries.end(),
                   [](const Entry& a, const Entry& b) { return a.log_time_ns < b.log_time_ns; });
}

}  // namespace uwbsar::rosbag::mcap

namespace uwbsar::rosbag::mcap {

bool Catalog::LoadChunkOrSkip(const Segment& s, ChunkMessages* out) {
  if (!skip_damaged_chunks) {
    LoadChunk(s, out);
    return true;
  }
  try {
    LoadChunk(s, out);
    return true;
  } catch (const InputError& e) {
    out->buffer.clear();
    out->entries.clear();
    ++skipped_chunks;
    const long long n = IndexedMessages(s);
    std::string damage = e.what();
    if (damage.rfind(Path() + ": ", 0) == 0) damage.erase(0, Path().size() + 2);
    Log(LogLevel::kWarning, Path() + ": skipping the damaged chunk at offset " +
                                std::to_string(s.offset) + " (" +
                                (n >= 0 ? std::to_string(n) : std::string("an unknown number of")) +
                                " messages, log time " + std::to_string(s.start_ns) + ".." +
                                std::to_string(s.end_ns) + " ns): " + damage);
    return false;
  }
}

long long Catalog::IndexedMessages(const Segment& s) const {
  long long count = -1;
  const std::uint64_t size = src_->Size();
  for (std::uint64_t pos = s.end; pos + kRecordHeaderBytes + 6 <= size;) {
    try {
      const auto [op, length] = RecordHeader(pos, size);
      if (op != kMessageIndex || length < 6) break;
      const auto head = ReadBytes(pos + kRecordHeaderBytes, 6);
      std::uint32_t records_bytes = 0;
      std::memcpy(&records_bytes, head.data() + 2, 4);
      count = std::max(count, 0LL) + records_bytes / 16;  // (log_time, offset) pairs
      pos += kRecordHeaderBytes + length;
    } catch (const InputError&) {
      break;
    }
  }
  return count;
}

}  // namespace uwbsar::rosbag::mcap
