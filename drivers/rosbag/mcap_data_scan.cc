#include "drivers/rosbag/mcap_data_scan.h"

#include <algorithm>

#include "core/errors.h"

namespace uwbsar::rosbag::mcap {
namespace {

// The scan's state between records: a record's effects are committed only once it has
// been read in full, so a record that throws leaves the catalog as it was before it.
class DataScanner {
 public:
  DataScanner(bool count, ScanMode mode, Catalog* catalog)
      : count_(count || mode == ScanMode::kRecover), mode_(mode), catalog_(*catalog) {}

  // Takes the record at `off` (content length `length`); false at DataEnd or a Footer.
  bool Take(std::uint8_t op, std::uint64_t off, std::uint64_t length) {
    const std::uint64_t content = off + kRecordHeaderBytes;
    const std::uint64_t next = content + length;
    if (op == kDataEnd || op == kFooter) return false;
    if (op == 0 && mode_ == ScanMode::kRecover) {
      // Reserved; zeros are what a file system leaves where a crash lost the data.
      catalog_.Fail("invalid opcode 0x00 at offset " + std::to_string(off));
    }
    if (op == kSchema || op == kChannel) {
      const auto bytes = catalog_.ReadBytes(content, length);
      Cursor c(bytes.data(), bytes.size(), catalog_.Path(), off, op);
      op == kSchema ? catalog_.AddSchema(c) : catalog_.AddChannel(c);
    } else if (op == kMessage) {
      const auto bytes =
          catalog_.ReadBytes(content, std::min<std::uint64_t>(length, kMessageHeaderBytes));
      Cursor c(bytes.data(), bytes.size(), catalog_.Path(), off, op);
      const std::uint16_t channel = c.U16();
      c.U32();
      const TimestampNs t = ToNs(c.U64(), c);
      c.U64();
      const int topic = catalog_.TopicOf(channel, c);
      if (count_) catalog_.Count(topic, t);
      if (in_run_ && t < run_.end_ns) EndRun();
      if (!in_run_) run_ = Segment{false, off, next, t, t};
      in_run_ = true;
      run_.end = next;
      run_.end_ns = t;
    } else if (op == kChunk) {
      const auto bytes = catalog_.ReadBytes(content, std::min<std::uint64_t>(length, 16));
      Cursor c(bytes.data(), bytes.size(), catalog_.Path(), off, op);
      Segment s{true, off, next, 0, 0};
      s.start_ns = ToNs(c.U64(), c);
      s.end_ns = ToNs(c.U64(), c);
      if (count_) {
        ChunkMessages chunk;
        if (mode_ == ScanMode::kRecover) {
          catalog_.LoadChunk(s, &chunk);  // recovery stops at the first damage
        } else if (!catalog_.LoadChunkOrSkip(s, &chunk)) {
          return true;  // skipped (skip_damaged_chunks): not a segment to merge
        }
        for (const Entry& e : chunk.entries) catalog_.Count(e.topic, e.log_time_ns);
      }
      EndRun();
      catalog_.segments.push_back(s);
    }
    return true;
  }

  void EndRun() {
    if (in_run_) catalog_.segments.push_back(run_);
    in_run_ = false;
  }

 private:
  const bool count_;
  const ScanMode mode_;
  Catalog& catalog_;
  Segment run_;
  bool in_run_ = false;
};

std::string WithoutPath(const std::string& what, const std::string& path) {
  const std::string prefix = path + ": ";
  return what.compare(0, prefix.size(), prefix) == 0 ? what.substr(prefix.size()) : what;
}

}  // namespace

ScanResult ScanDataSection(std::uint64_t end, bool count, ScanMode mode, Catalog* catalog) {
  ScanResult result;
  DataScanner scanner(count, mode, catalog);
  std::uint64_t off = sizeof(kMagic);
  if (off >= end) catalog->Fail("truncated: no Header record after the magic");
  {
    const auto [op, length] = catalog->RecordHeader(off, end);
    if (op != kHeader) {
      catalog->Fail("corrupt: the first record is " + OpcodeName(op) + ", not Header");
    }
    off += kRecordHeaderBytes + length;
  }
  while (off < end) {
    try {
      const auto [op, length] = catalog->RecordHeader(off, end);
      if (!scanner.Take(op, off, length)) break;
      off += kRecordHeaderBytes + length;
    } catch (const InputError& e) {
      if (mode == ScanMode::kStrict) throw;
      result.complete = false;
      result.stop_reason = WithoutPath(e.what(), catalog->Path());
      break;
    }
  }
  scanner.EndRun();
  result.readable_end = off;
  return result;
}

}  // namespace uwbsar::rosbag::mcap
