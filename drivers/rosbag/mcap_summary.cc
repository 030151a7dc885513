#include "drivers/rosbag/mcap_summary.h"

#include <cstring>
#include <map>

#include "drivers/rosbag/crc32.h"

namespace uwbsar::rosbag::mcap {

bool ReadFooter(const Catalog& catalog, Footer* footer, std::string* why_not) {
  const std::uint64_t size = catalog.Source().Size();
  const std::uint64_t min_size =
      2 * sizeof(kMagic) + kRecordHeaderBytes + kRecordHeaderBytes + kFooterContentBytes;
  if (size < min_size) {
    *why_not = std::to_string(size) + " bytes is too short for a Footer";
    return false;
  }
  std::uint8_t magic[sizeof(kMagic)];
  catalog.Source().ReadAt(size - sizeof(kMagic), sizeof(kMagic), magic);
  if (std::memcmp(magic, kMagic, sizeof(kMagic)) != 0) {
    *why_not = "no MCAP magic at the end of the file";
    return false;
  }
  footer->at = size - sizeof(kMagic) - kRecordHeaderBytes - kFooterContentBytes;
  const auto bytes = catalog.ReadBytes(footer->at, kRecordHeaderBytes + kFooterContentBytes);
  std::uint64_t length = 0;
  std::memcpy(&length, bytes.data() + 1, 8);
  if (bytes[0] != kFooter || length != kFooterContentBytes) {
    *why_not = "no Footer record before the closing magic";
    return false;
  }
  Cursor c(bytes.data() + kRecordHeaderBytes, kFooterContentBytes, catalog.Path(), footer->at,
           kFooter);
  footer->summary_start = c.U64();
  footer->summary_offset_start = c.U64();
  footer->summary_crc = c.U32();
  return true;
}

std::uint64_t DataSectionEnd(const Footer& footer) {
  const bool in_range = footer.summary_start >= sizeof(kMagic) && footer.summary_start <= footer.at;
  return footer.summary_start != 0 && in_range ? footer.summary_start : footer.at;
}

bool ReadSummary(const Footer& footer, Catalog* catalog) {
  if (footer.summary_start == 0) return false;
  if (DataSectionEnd(footer) != footer.summary_start) {
    catalog->Fail("corrupt Footer: summary_start " + std::to_string(footer.summary_start) +
                  " is outside the file");
  }
  if (footer.summary_crc != 0) {
    // The CRC covers the summary up to and including the Footer's summary_offset_start.
    const auto bytes = catalog->ReadBytes(
        footer.summary_start, footer.at + kRecordHeaderBytes + 16 - footer.summary_start);
    const std::uint32_t crc = Crc32(0, bytes.data(), bytes.size());
    if (crc != footer.summary_crc) {
      catalog->Fail("summary CRC mismatch: Footer says " + Hex(footer.summary_crc) +
                    ", the bytes give " + Hex(crc));
    }
  }
  const std::uint64_t end =
      (footer.summary_offset_start >= footer.summary_start &&
       footer.summary_offset_start <= footer.at && footer.summary_offset_start != 0)
          ? footer.summary_offset_start
          : footer.at;
  bool have_stats = false;
  std::map<std::uint16_t, std::uint64_t> counts;
  for (std::uint64_t off = footer.summary_start; off < end;) {
    const auto [op, length] = catalog->RecordHeader(off, end);
    const std::uint64_t content = off + kRecordHeaderBytes;
    if (op == kSchema || op == kChannel || op == kStatistics) {
      const auto bytes = catalog->ReadBytes(content, length);
      Cursor c(bytes.data(), bytes.size(), catalog->Path(), off, op);
      if (op == kSchema) catalog->AddSchema(c);
      if (op == kChannel) catalog->AddChannel(c);
      if (op == kStatistics) {
        StorageStats& stats = catalog->stats;
        stats.message_count = c.U64();
        c.U16();  // schema_count
        c.U32();  // channel_count
        c.U32();  // attachment_count
        c.U32();  // metadata_count
        c.U32();  // chunk_count
        stats.start_ns = ToNs(c.U64(), c);
        stats.end_ns = ToNs(c.U64(), c);
        for (const auto& [id, n] : c.U16U64Map()) counts[id] = n;
        have_stats = true;
      }
    }
    off = content + length;
  }
  if (!have_stats || catalog->topics.empty()) {
    catalog->ResetCounts();
    return false;
  }
  catalog->SetChannelCounts(counts);
  return true;
}

}  // namespace uwbsar::rosbag::mcap
