// metadata.yaml of a rosbag2 bag directory (root `rosbag2_bagfile_information`),
// versions 1-9 (Foxy 4, Galactic 5, Humble 5, Iron 7-8, Jazzy 9). Newer versions only
// add fields, so unknown fields are ignored; what a reader needs is checked.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "drivers/rosbag/bag_storage.h"

namespace uwbsar::rosbag {

struct BagFileInfo {
  std::string path;  ///< relative to the bag directory
  TimestampNs starting_time_ns = 0;
  std::int64_t duration_ns = 0;
  std::uint64_t message_count = 0;
};

struct BagMetadata {
  int version = 5;
  std::string storage_identifier;  ///< "sqlite3" or "mcap"
  std::vector<std::string> relative_file_paths;
  TimestampNs starting_time_ns = 0;
  std::int64_t duration_ns = 0;
  std::uint64_t message_count = 0;
  std::vector<TopicInfo> topics;   ///< with message_count; no definitions
  std::string compression_format;  ///< "" or "zstd"
  std::string compression_mode;    ///< "", "FILE" or "MESSAGE" (any case)
  std::vector<BagFileInfo> files;  ///< version >= 5
  std::string ros_distro;          ///< version >= 8
};

/// Parses a metadata.yaml; throws InputError naming the file, line and field.
BagMetadata ReadBagMetadata(const std::string& path);
/// Parses metadata text; `name` stands for the file in messages.
BagMetadata ParseBagMetadata(const std::string& text, const std::string& name);
/// Serializes as rosbag2 of `metadata.version` writes it (root key included).
std::string BagMetadataToYaml(const BagMetadata& metadata);

}  // namespace uwbsar::rosbag
