#include "drivers/rosbag/mcap_storage_reader.h"

#include <algorithm>
#include <cstring>
#include <limits>
#include <queue>

#include "core/errors.h"
#include "core/log.h"
#include "drivers/rosbag/mcap_catalog.h"
#include "drivers/rosbag/mcap_data_scan.h"
#include "drivers/rosbag/mcap_format.h"
#include "drivers/rosbag/mcap_summary.h"

namespace uwbsar::rosbag {
namespace {

using mcap::Catalog;
using mcap::Cursor;
using mcap::Entry;
using mcap::Segment;

struct SegmentIterator {
  bool is_chunk = false;
  int order = 0;                   // segment index: ties in log time go in file order
  mcap::ChunkMessages chunk;       // decompressed chunk, or the current loose record
  std::size_t next = 0;            // chunk: index of the head entry
  std::uint64_t pos = 0, end = 0;  // loose run: file range still to read
  Entry head;
};

struct HeadLater {
  bool operator()(const SegmentIterator* a, const SegmentIterator* b) const {
    if (a->head.log_time_ns != b->head.log_time_ns)
      return a->head.log_time_ns > b->head.log_time_ns;
    return a->order > b->order;
  }
};

class McapStorageReader final : public StorageReader {
 public:
  McapStorageReader(std::unique_ptr<ByteSource> source, McapOpenReport* report,
                    const BagReadOptions& options)
      : src_(std::move(source)), catalog_(*src_) {
    catalog_.skip_damaged_chunks = options.skip_damaged_chunks;
    McapOpenReport local;
    Open(report ? report : &local);
    std::stable_sort(catalog_.segments.begin(), catalog_.segments.end(),
                     [](const Segment& a, const Segment& b) { return a.start_ns < b.start_ns; });
    catalog_.FreezeTopics();
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
  const std::vector<TopicInfo>& Topics() override { return catalog_.topics; }
  StorageStats Stats() override { return catalog_.stats; }

  bool Next(StorageMessage* msg) override {
    if (pending_) {
      if (Advance(pending_)) {
        heap_.push(pending_);
      } else {
        delete pending_;
      }
      pending_ = nullptr;
    }
    // Open every segment that may hold a message before the current earliest head.
    const std::vector<Segment>& segments = catalog_.segments;
    while (next_segment_ < segments.size() &&
           (heap_.empty() || segments[next_segment_].start_ns <= heap_.top()->head.log_time_ns)) {
      auto it = std::make_unique<SegmentIterator>();
      it->order = static_cast<int>(next_segment_);
      const Segment& s = segments[next_segment_++];
      it->is_chunk = s.is_chunk;
      if (s.is_chunk) {
        if (!catalog_.LoadChunkOrSkip(s, &it->chunk)) continue;
      } else {
        it->pos = s.offset;
        it->end = s.end;
      }
      if (Advance(it.get())) heap_.push(it.release());
    }
    if (heap_.empty()) return false;
    pending_ = heap_.top();
    heap_.pop();
    // The merge is only as good as the file's time ranges: a segment whose messages start
    // before its declared start would come out late. Refuse rather than mis-order.
    if (pending_->head.log_time_ns < last_log_time_ns_) {
      catalog_.Fail("message at log time " + std::to_string(pending_->head.log_time_ns) +
                    " ns follows one at " + std::to_string(last_log_time_ns_) +
                    " ns: the file's chunk time ranges are inconsistent");
    }
    last_log_time_ns_ = pending_->head.log_time_ns;
    msg->topic = pending_->head.topic;
    msg->log_time_ns = pending_->head.log_time_ns;
    msg->data = pending_->chunk.buffer.data() + pending_->head.offset;
    msg->size = pending_->head.size;
    return true;
  }

 private:
  void Open(McapOpenReport* report) {
    const std::uint64_t size = src_->Size();
    report->file_size = size;
    std::uint8_t magic[sizeof(mcap::kMagic)] = {};
    src_->ReadAt(0, std::min<std::uint64_t>(size, sizeof(magic)), magic);
    if (size < sizeof(magic) || std::memcmp(magic, mcap::kMagic, sizeof(magic)) != 0) {
      catalog_.Fail("bad magic: not an MCAP file (expected 89 4D 43 41 50 30 0D 0A)");
    }
    mcap::Footer footer;
    if (!mcap::ReadFooter(catalog_, &footer, &report->reason)) {
      Recover(report);
      return;
    }
    bool summary_complete = false;
    try {
      summary_complete = mcap::ReadSummary(footer, &catalog_);
    } catch (const InputError& e) {
      // The data section does not depend on the summary: read it on its own.
      catalog_ = Catalog(*src_);
      report->summary_ignored = true;
      report->reason = e.what();
      Log(LogLevel::kWarning,
          report->reason + "; ignoring the summary and reading the data section");
    }
    mcap::ScanDataSection(mcap::DataSectionEnd(footer), !summary_complete, mcap::ScanMode::kStrict,
                          &catalog_);
  }

  // A file cut short: keep what a linear scan can verify, and say what was lost.
  void Recover(McapOpenReport* report) {
    const mcap::ScanResult scan =
        mcap::ScanDataSection(src_->Size(), true, mcap::ScanMode::kRecover, &catalog_);
    report->recovered = true;
    report->readable_end = scan.readable_end;
    report->recovered_messages = catalog_.stats.message_count;
    std::string what = Path() + ": MCAP file has no footer (" + report->reason +
                       "; recording cut short?): recovered " +
                       std::to_string(catalog_.stats.message_count) + " messages from the first " +
                       std::to_string(scan.readable_end) + " of " + std::to_string(src_->Size()) +
                       " bytes";
    if (!scan.complete) {
      report->reason +=
          "; unreadable from offset " + std::to_string(scan.readable_end) + ": " + scan.stop_reason;
      what +=
          "; unreadable from offset " + std::to_string(scan.readable_end) + ": " + scan.stop_reason;
    }
    Log(LogLevel::kWarning, what);
  }

  // Moves the iterator to its next message; false when it has none.
  bool Advance(SegmentIterator* it) {
    if (it->is_chunk) {
      if (it->next >= it->chunk.entries.size()) return false;
      it->head = it->chunk.entries[it->next++];
      return true;
    }
    while (it->pos < it->end) {
      const auto [op, length] = catalog_.RecordHeader(it->pos, it->end);
      const std::uint64_t at = it->pos;
      it->pos += mcap::kRecordHeaderBytes + length;
      if (op != mcap::kMessage) continue;
      it->chunk.buffer = catalog_.ReadBytes(at + mcap::kRecordHeaderBytes, length);
      Cursor c(it->chunk.buffer.data(), it->chunk.buffer.size(), Path(), at, op);
      const std::uint16_t channel = c.U16();
      c.U32();
      it->head.log_time_ns = mcap::ToNs(c.U64(), c);
      c.U64();
      it->head.topic = catalog_.TopicOf(channel, c);
      it->head.offset = mcap::kMessageHeaderBytes;
      it->head.size = it->chunk.buffer.size() - mcap::kMessageHeaderBytes;
      return true;
    }
    return false;
  }

  std::unique_ptr<ByteSource> src_;
  Catalog catalog_;
  std::size_t next_segment_ = 0;
  TimestampNs last_log_time_ns_ = std::numeric_limits<TimestampNs>::min();
  std::priority_queue<SegmentIterator*, std::vector<SegmentIterator*>, HeadLater> heap_;
  SegmentIterator* pending_ = nullptr;
};

}  // namespace

std::unique_ptr<StorageReader> OpenMcapStorage(std::unique_ptr<ByteSource> source,
                                               McapOpenReport* report,
                                               const BagReadOptions& options) {
  return std::make_unique<McapStorageReader>(std::move(source), report, options);
}

std::unique_ptr<StorageReader> OpenMcapStorage(const std::string& path,
                                               const BagReadOptions& options) {
  return OpenMcapStorage(OpenFileSource(path), nullptr, options);
}

}  // namespace uwbsar::rosbag
