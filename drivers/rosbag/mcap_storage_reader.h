// MCAP storage reader (ros2 profile). Works with or without the summary section:
// the data section is always walked record by record (cheap: chunk bodies are
// skipped), and when the summary lacks channels or statistics every chunk is also
// decompressed once up front to find them. Messages are then merged across chunks
// and runs of loose (unchunked) messages in log-time order, decompressing a chunk
// only when its time range is reached, so memory stays at a few chunks.
//
// Crash recovery: a file without its Footer and closing magic (a recording cut short
// by a crash or power loss) is read like `mcap recover` does, by a linear scan from
// the Header that stops at the first cut or damaged record and keeps every complete
// message before it (the contract is in mcap_data_scan.h); a Footer whose summary is
// unreadable makes the reader ignore the summary. Both log a warning naming the file.
// A file with an intact Footer but a damaged data section is an InputError, unless
// BagReadOptions::skip_damaged_chunks: then a damaged chunk is skipped with a warning
// naming its offset and how many messages it held (from its MessageIndex records).
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "drivers/rosbag/bag_storage.h"
#include "drivers/rosbag/byte_source.h"

namespace uwbsar::rosbag {

/// How an MCAP file was opened, beyond what the warning says.
struct McapOpenReport {
  bool recovered = false;        ///< no usable Footer: read by a recovering linear scan
  bool summary_ignored = false;  ///< Footer intact, summary unreadable: data section scanned
  std::uint64_t file_size = 0;
  std::uint64_t readable_end = 0;  ///< recovered: bytes at the start of the file that were used
  std::uint64_t recovered_messages = 0;
  std::string reason;  ///< why the Footer or summary was not used, and where the scan stopped
};

/// Opens MCAP data from any source (a file, or memory for tests and fuzzing); fills
/// `report` when given.
std::unique_ptr<StorageReader> OpenMcapStorage(std::unique_ptr<ByteSource> source,
                                               McapOpenReport* report = nullptr,
                                               const BagReadOptions& options = {});

}  // namespace uwbsar::rosbag
