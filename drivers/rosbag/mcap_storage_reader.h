// MCAP storage reader (ros2 profile). Works with or without the summary section:
// the data section is always walked record by record (cheap: chunk bodies are
// skipped), and when the summary lacks channels or statistics every chunk is also
// decompressed once up front to find them. Messages are then merged across chunks
// and runs of loose (unchunked) messages in log-time order, decompressing a chunk
// only when its time range is reached, so memory stays at a few chunks.
#pragma once

#include <memory>

#include "drivers/rosbag/bag_storage.h"
#include "drivers/rosbag/byte_source.h"

namespace uwbsar::rosbag {

/// Opens MCAP data from any source (a file, or memory for tests and fuzzing).
std::unique_ptr<StorageReader> OpenMcapStorage(std::unique_ptr<ByteSource> source);

}  // namespace uwbsar::rosbag
