// A checksum beside every blob of the session file (format version 8): a blob column `<name>`
// has a column `<name>_xxh3` holding XXH3-64 of the blob's bytes (xxHash, libxxhash), stored
// as sqlite's signed 64-bit integer. zstd frames carry no checksum of their own, so bytes
// flipped inside a tile's body would otherwise decode into a plausible, wrong tile; the reader
// (TableReader::Blob) compares the two before anything is decoded. Files of version 7 and
// older have no such columns and are read without this check.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace uwbsar::session {

/// The first format version whose blob columns have checksums.
inline constexpr int kFirstChecksummedVersion = 8;

/// XXH3-64 of `blob`, as the signed integer sqlite stores.
std::int64_t BlobChecksum(const std::vector<unsigned char>& blob);

/// The name of the checksum column of blob column `blob_column` ("tile" -> "tile_xxh3").
std::string ChecksumColumn(const std::string& blob_column);

/// `columns` of a table, with the checksum columns of its `blobs` where `format_version` has
/// them (what a TableReader requires).
std::vector<std::string> WithChecksums(int format_version, std::vector<std::string> columns,
                                       const std::vector<std::string>& blobs);

}  // namespace uwbsar::session
