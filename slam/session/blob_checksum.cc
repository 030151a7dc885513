#include "slam/session/blob_checksum.h"

#include <xxhash.h>

namespace uwbsar::session {

std::int64_t BlobChecksum(const std::vector<unsigned char>& blob) {
  // The same 64 bits either way: sqlite has no unsigned integers.
  return static_cast<std::int64_t>(XXH3_64bits(blob.data(), blob.size()));
}

std::string ChecksumColumn(const std::string& blob_column) { return blob_column + "_xxh3"; }

std::vector<std::string> WithChecksums(int format_version, std::vector<std::string> columns,
                                       const std::vector<std::string>& blobs) {
  if (format_version < kFirstChecksummedVersion) return columns;
  for (const std::string& blob : blobs) columns.push_back(ChecksumColumn(blob));
  return columns;
}

}  // namespace uwbsar::session
