// Walking an MCAP data section record by record from the Header, as the reader does
// for every file (to list the chunks and loose messages it will merge) and as
// `mcap recover` does for a file cut short (no Footer, no summary).
//
// Recovery contract: the scan stops at the first record that is cut short or damaged
// and keeps every complete record before it. A Chunk is taken whole or not at all:
// it must be complete, decompress to its declared size and match its CRC (when it has
// one), and only then are its messages kept; the messages of a chunk that is cut or
// fails its CRC are lost, even those whose bytes look complete, because nothing
// vouches for them. So what a crash loses is the chunk being written: the writer
// closes the chunk on every Flush() (mcap_storage_writer.cc).
#pragma once

#include <cstdint>
#include <string>

#include "drivers/rosbag/mcap_catalog.h"

namespace uwbsar::rosbag::mcap {

enum class ScanMode {
  kStrict,   ///< any damage throws InputError (a file with an intact Footer)
  kRecover,  ///< stop cleanly at the first damaged record (a file cut short)
};

struct ScanResult {
  bool complete = true;            ///< reached DataEnd, a Footer or `end` without damage
  std::uint64_t readable_end = 0;  ///< one past the last record taken
  std::string stop_reason;         ///< why the scan stopped early (kRecover only)
};

/// Scans the data section [8, end): registers schemas and channels in `catalog`,
/// appends its segments (chunks and runs of loose messages, in file order) and, when
/// `count` (always in kRecover, which must verify every chunk), decompresses each chunk
/// to count its messages. A damaged or missing Header record throws in both modes:
/// without it there is nothing to recover.
ScanResult ScanDataSection(std::uint64_t end, bool count, ScanMode mode, Catalog* catalog);

}  // namespace uwbsar::rosbag::mcap
