// CRC-32 (ISO-HDLC, the zlib/PNG polynomial 0xEDB88320) as MCAP uses it for chunk,
// data-section and summary checksums. Slice-by-8 so that checking a chunk costs
// little next to decompressing it.
#pragma once

#include <cstddef>
#include <cstdint>

namespace uwbsar::rosbag {

/// Continues a CRC: Crc32(Crc32(0, a), b) == Crc32 of a followed by b. Crc32(0, "123456789")
/// is 0xCBF43926.
std::uint32_t Crc32(std::uint32_t crc, const void* data, std::size_t size);

}  // namespace uwbsar::rosbag
