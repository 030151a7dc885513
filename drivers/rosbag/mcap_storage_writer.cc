// MCAP storage writer with the `ros2` profile, as rosbag2's MCAP plugin writes it:
// schema records hold the ros2msg definitions, channels carry the QoS metadata,
// messages go into compressed chunks each followed by its message indexes, and Close()
// writes the summary (schemas, channels, statistics, chunk indexes, metadata index),
// summary offsets and a footer with CRCs, so indexed readers (Foxglove, `ros2 bag`,
// `mcap info`) open the file without scanning it.
//
// Crash safety: a file cut short has no summary, and the reader recovers it by a
// linear scan that keeps whole, CRC-checked chunks only (mcap_data_scan.h). So Flush()
// closes the open chunk, writes it with its message indexes and fsyncs: after a crash
// or power loss, every message written before the last Flush() is recoverable.
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <limits>
#include <map>

#include "core/errors.h"
#include "drivers/rosbag/bag_storage.h"
#include "drivers/rosbag/crc32.h"
#include "drivers/rosbag/mcap_format.h"

namespace uwbsar::rosbag {
namespace {

using mcap::Builder;

class McapStorageWriter final : public StorageWriter {
 public:
  McapStorageWriter(const std::string& path, const McapWriteOptions& options)
      : path_(path), options_(options) {
    if (!options_.compression.empty() && options_.compression != "zstd" &&
        options_.compression != "lz4") {
      throw InputError(path + ": unknown MCAP chunk compression '" + options_.compression +
                       "' (supported: none, zstd, lz4)");
    }
    file_ = std::fopen(path.c_str(), "wbx");
    if (!file_) throw InputError(path + ": cannot create: " + std::strerror(errno));
    std::vector<std::uint8_t> out;
    Builder b(&out);
    b.Raw(mcap::kMagic, sizeof(mcap::kMagic));
    const std::size_t at = b.BeginRecord(mcap::kHeader);
    b.String("ros2");
    b.String("uwbsar");
    b.EndRecord(at);
    Emit(out);
  }

  ~McapStorageWriter() override {
    if (file_) std::fclose(file_);
  }

  void AddTopic(const TopicInfo& topic) override {
    std::vector<std::uint8_t> out;
    Builder b(&out);
    std::uint16_t schema_id = 0;
    if (!topic.type.empty()) {
      auto it = schema_ids_.find(topic.type);
      if (it == schema_ids_.end()) {
        schema_id = static_cast<std::uint16_t>(schema_ids_.size() + 1);
        it = schema_ids_.emplace(topic.type, schema_id).first;
        schema_records_.emplace_back();
        Builder s(&schema_records_.back());
        const std::size_t at = s.BeginRecord(mcap::kSchema);
        s.U16(schema_id);
        s.String(topic.type);
        s.String(topic.definition_encoding.empty() ? "ros2msg" : topic.definition_encoding);
        s.String(topic.message_definition);
        s.EndRecord(at);
        b.Raw(schema_records_.back().data(), schema_records_.back().size());
      }
      schema_id = it->second;
    }
    const auto channel_id = static_cast<std::uint16_t>(channel_records_.size() + 1);
    channel_records_.emplace_back();
    Builder c(&channel_records_.back());
    const std::size_t at = c.BeginRecord(mcap::kChannel);
    c.U16(channel_id);
    c.U16(schema_id);
    c.String(topic.name);
    c.String(topic.serialization_format);
    std::vector<std::uint8_t> map;
    Builder m(&map);
    m.String("offered_qos_profiles");
    m.String(topic.offered_qos_profiles);
    c.U32(static_cast<std::uint32_t>(map.size()));
    c.Raw(map.data(), map.size());
    c.EndRecord(at);
    b.Raw(channel_records_.back().data(), channel_records_.back().size());
    channel_counts_[channel_id] = 0;
    // Written outside chunks, before any chunk that uses them: linear readers find
    // them first. The open chunk is written later, so ordering holds.
    Emit(out);
  }

  void Write(int topic, TimestampNs log_time_ns, const std::uint8_t* data,
             std::size_t size) override {
    const auto channel = static_cast<std::uint16_t>(topic + 1);
    const auto t = static_cast<std::uint64_t>(log_time_ns);
    if (chunk_.empty()) chunk_start_ = chunk_end_ = t;
    chunk_start_ = std::min(chunk_start_, t);
    chunk_end_ = std::max(chunk_end_, t);
    message_start_ = message_count_ == 0 ? t : std::min(message_start_, t);
    message_end_ = message_count_ == 0 ? t : std::max(message_end_, t);
    chunk_index_[channel].emplace_back(t, chunk_.size());
    Builder b(&chunk_);
    const std::size_t at = b.BeginRecord(mcap::kMessage);
    b.U16(channel);
    b.U32(sequence_[channel]++);
    b.U64(t);
    b.U64(t);
    b.Raw(data, size);
    b.EndRecord(at);
    ++channel_counts_[channel];
    ++message_count_;
    if (chunk_.size() >= options_.chunk_size_bytes) CloseChunk();
  }

  void Flush() override {
    CloseChunk();
    if (std::fflush(file_) != 0) Fail("write");
    if (::fsync(::fileno(file_)) != 0) Fail("sync");
  }

  void Close(const std::string& metadata_yaml) override {
    CloseChunk();
    const Span metadata = WriteMetadata(metadata_yaml);
    std::vector<std::uint8_t> out;
    Builder b(&out);
    const std::size_t at = b.BeginRecord(mcap::kDataEnd);
    b.U32(data_crc_);
    b.EndRecord(at);
    Emit(out);

    const std::uint64_t summary_start = position_;
    std::vector<std::uint8_t> summary;
    const std::vector<SummaryGroup> groups = BuildSummary(metadata, summary_start, &summary);
    AppendSummaryOffsetsAndFooter(groups, summary_start, &summary);
    WriteRaw(summary);
    if (std::fclose(file_) != 0) {
      file_ = nullptr;
      Fail("close");
    }
    file_ = nullptr;
  }

 private:
  [[noreturn]] void Fail(const char* what) const {
    throw InputError(path_ + ": cannot " + std::string(what) + ": " + std::strerror(errno));
  }

  /// Where a record or a group of records lies in the file.
  struct Span {
    std::uint64_t start = 0, length = 0;
  };
  /// A group of summary records of one opcode, listed in a Summary Offset record.
  struct SummaryGroup {
    std::uint8_t opcode;
    std::uint64_t start, length;
  };

  /// Writes the rosbag2 metadata record (the bag's metadata.yaml) into the data section.
  Span WriteMetadata(const std::string& metadata_yaml) {
    std::vector<std::uint8_t> out;
    Builder b(&out);
    Span span;
    span.start = position_;
    const std::size_t at = b.BeginRecord(mcap::kMetadata);
    b.String("rosbag2");
    std::vector<std::uint8_t> map;
    Builder m(&map);
    m.String("serialized_metadata");
    m.String(metadata_yaml);
    b.U32(static_cast<std::uint32_t>(map.size()));
    b.Raw(map.data(), map.size());
    b.EndRecord(at);
    span.length = out.size();
    Emit(out);
    return span;
  }

  /// Appends the summary section (schemas, channels, statistics, chunk indexes, metadata
  /// index) to `summary`, which starts at file offset `summary_start`; returns its groups.
  std::vector<SummaryGroup> BuildSummary(const Span& metadata, std::uint64_t summary_start,
                                         std::vector<std::uint8_t>* summary) const {
    Builder s(summary);
    std::vector<SummaryGroup> groups;
    auto group = [&](std::uint8_t opcode, auto&& write) {
      const std::size_t begin = summary->size();
      write();
      if (summary->size() > begin) {
        groups.push_back({opcode, summary_start + begin, summary->size() - begin});
      }
    };
    group(mcap::kSchema, [&] {
      for (const auto& r : schema_records_) s.Raw(r.data(), r.size());
    });
    group(mcap::kChannel, [&] {
      for (const auto& r : channel_records_) s.Raw(r.data(), r.size());
    });
    group(mcap::kStatistics, [&] { AppendStatistics(&s); });
    group(mcap::kChunkIndex, [&] {
      for (const auto& r : chunk_indexes_) s.Raw(r.data(), r.size());
    });
    group(mcap::kMetadataIndex, [&] {
      const std::size_t a = s.BeginRecord(mcap::kMetadataIndex);
      s.U64(metadata.start);
      s.U64(metadata.length);
      s.String("rosbag2");
      s.EndRecord(a);
    });
    return groups;
  }

  void AppendStatistics(Builder* s) const {
    const std::size_t a = s->BeginRecord(mcap::kStatistics);
    s->U64(message_count_);
    s->U16(static_cast<std::uint16_t>(schema_records_.size()));
    s->U32(static_cast<std::uint32_t>(channel_records_.size()));
    s->U32(0);  // attachments
    s->U32(1);  // metadata
    s->U32(static_cast<std::uint32_t>(chunk_indexes_.size()));
    s->U64(message_start_);
    s->U64(message_end_);
    s->U32(static_cast<std::uint32_t>(channel_counts_.size() * 10));
    for (const auto& [id, n] : channel_counts_) {
      s->U16(id);
      s->U64(n);
    }
    s->EndRecord(a);
  }

  /// Appends the summary offsets and the footer (with the summary CRC) and the magic.
  static void AppendSummaryOffsetsAndFooter(const std::vector<SummaryGroup>& groups,
                                            std::uint64_t summary_start,
                                            std::vector<std::uint8_t>* summary) {
    Builder s(summary);
    const std::uint64_t summary_offset_start = summary_start + summary->size();
    for (const SummaryGroup& g : groups) {
      const std::size_t a = s.BeginRecord(mcap::kSummaryOffset);
      s.U8(g.opcode);
      s.U64(g.start);
      s.U64(g.length);
      s.EndRecord(a);
    }
    s.U8(mcap::kFooter);
    s.U64(mcap::kFooterContentBytes);
    s.U64(summary_start);
    s.U64(summary_offset_start);
    s.U32(Crc32(0, summary->data(), summary->size()));  // covers the footer up to here
    s.Raw(mcap::kMagic, sizeof(mcap::kMagic));
  }

  void WriteRaw(const std::vector<std::uint8_t>& bytes) {
    if (!bytes.empty() && std::fwrite(bytes.data(), 1, bytes.size(), file_) != bytes.size()) {
      Fail("write");
    }
    position_ += bytes.size();
  }

  // Writes data-section bytes, keeping the data-section CRC.
  void Emit(const std::vector<std::uint8_t>& bytes) {
    data_crc_ = Crc32(data_crc_, bytes.data(), bytes.size());
    WriteRaw(bytes);
  }

  void CloseChunk() {
    if (chunk_.empty()) return;
    std::vector<std::uint8_t> compressed;
    mcap::Compress(options_.compression, chunk_, &compressed);
    std::vector<std::uint8_t> out;
    Builder b(&out);
    const std::uint64_t chunk_at = position_;
    std::size_t at = b.BeginRecord(mcap::kChunk);
    b.U64(chunk_start_);
    b.U64(chunk_end_);
    b.U64(chunk_.size());
    b.U32(Crc32(0, chunk_.data(), chunk_.size()));
    b.String(options_.compression);
    b.U64(compressed.size());
    b.Raw(compressed.data(), compressed.size());
    b.EndRecord(at);
    const std::uint64_t chunk_length = out.size();
    std::vector<std::pair<std::uint16_t, std::uint64_t>> index_offsets;
    for (const auto& [channel, entries] : chunk_index_) {
      index_offsets.emplace_back(channel, chunk_at + out.size());
      at = b.BeginRecord(mcap::kMessageIndex);
      b.U16(channel);
      b.U32(static_cast<std::uint32_t>(entries.size() * 16));
      for (const auto& [t, offset] : entries) {
        b.U64(t);
        b.U64(offset);
      }
      b.EndRecord(at);
    }
    const std::uint64_t index_length = out.size() - chunk_length;
    Emit(out);

    chunk_indexes_.emplace_back();
    Builder ci(&chunk_indexes_.back());
    at = ci.BeginRecord(mcap::kChunkIndex);
    ci.U64(chunk_start_);
    ci.U64(chunk_end_);
    ci.U64(chunk_at);
    ci.U64(chunk_length);
    ci.U32(static_cast<std::uint32_t>(index_offsets.size() * 10));
    for (const auto& [channel, offset] : index_offsets) {
      ci.U16(channel);
      ci.U64(offset);
    }
    ci.U64(index_length);
    ci.String(options_.compression);
    ci.U64(compressed.size());
    ci.U64(chunk_.size());
    ci.EndRecord(at);
    chunk_.clear();
    chunk_index_.clear();
  }

  std::string path_;
  McapWriteOptions options_;
  std::FILE* file_ = nullptr;
  std::uint64_t position_ = 0;
  std::uint32_t data_crc_ = 0;
  std::map<std::string, std::uint16_t> schema_ids_;
  std::vector<std::vector<std::uint8_t>> schema_records_, channel_records_, chunk_indexes_;
  std::map<std::uint16_t, std::uint64_t> channel_counts_;
  std::map<std::uint16_t, std::uint32_t> sequence_;
  std::uint64_t message_count_ = 0, message_start_ = 0, message_end_ = 0;
  std::vector<std::uint8_t> chunk_;
  std::uint64_t chunk_start_ = 0, chunk_end_ = 0;
  std::map<std::uint16_t, std::vector<std::pair<std::uint64_t, std::uint64_t>>> chunk_index_;
};

}  // namespace

std::unique_ptr<StorageWriter> CreateMcapStorage(const std::string& path,
                                                 const McapWriteOptions& options) {
  return std::make_unique<McapStorageWriter>(path, options);
}

}  // namespace uwbsar::rosbag
