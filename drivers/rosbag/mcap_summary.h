// The indexed way into an MCAP file: the Footer before the closing magic and the
// summary section it points to (schemas, channels, statistics). A file cut short has
// neither; the reader then falls back to walking the data section (mcap_data_scan.h).
#pragma once

#include <cstdint>
#include <string>

#include "drivers/rosbag/mcap_catalog.h"

namespace uwbsar::rosbag::mcap {

struct Footer {
  std::uint64_t at = 0;  ///< offset of the Footer record
  std::uint64_t summary_start = 0;
  std::uint64_t summary_offset_start = 0;
  std::uint32_t summary_crc = 0;
};

/// Reads the Footer record that closes the file. Returns false, saying why in
/// `why_not`, when the file does not end in a well-formed Footer and the magic (a
/// recording cut short); the caller has checked the opening magic.
bool ReadFooter(const Catalog& catalog, Footer* footer, std::string* why_not);

/// Where the data section ends: the summary start, or the Footer when there is no
/// summary (or its start is out of range, which ReadSummary reports).
std::uint64_t DataSectionEnd(const Footer& footer);

/// Reads the summary's schemas, channels and statistics into `catalog`. Returns true
/// when it has channels and statistics, so no chunk needs opening to count messages;
/// false when there is no summary or it lacks them. Throws InputError when the summary
/// is damaged (start out of range, CRC mismatch, a record overrunning it).
bool ReadSummary(const Footer& footer, Catalog* catalog);

}  // namespace uwbsar::rosbag::mcap
