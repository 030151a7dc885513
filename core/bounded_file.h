// Every file uwbsar reads is first checked, without opening it (opening a FIFO waits for a
// writer), to be a regular file within a size budget: a path to /dev/zero, a FIFO, a socket
// or a huge file must give one clear error, not hang or fill the memory (docs/refusals.md).
// Small text files (configuration, map_server YAML, bag metadata.yaml) are read whole.
#pragma once

#include <cstdint>
#include <fstream>
#include <limits>
#include <string>

namespace uwbsar {

/// The largest YAML file uwbsar reads (configuration, map YAML, bag metadata).
constexpr std::uintmax_t kMaxYamlFileBytes = 4u << 20;  // 4 MiB

/// No size budget: a file read in parts, never whole (a bag's storage, a session, an image
/// whose declared size is checked instead).
constexpr std::uintmax_t kAnyFileSize = std::numeric_limits<std::uintmax_t>::max();

/// Checks `path` (links followed) without opening it and returns its size. Throws InputError,
/// one line naming the path and `what` (e.g. "trajectory"), when it does not exist, is not a
/// regular file ("is not a regular file (a FIFO)": a folder, FIFO, socket or device) or holds
/// more than `max_bytes`; `budget` names the setting that sets the budget (e.g.
/// "limits.max_input_file_mb"), empty for a fixed one.
std::uintmax_t CheckInputFile(const std::string& path, const std::string& what,
                              std::uintmax_t max_bytes = kAnyFileSize,
                              const std::string& budget = "");

/// `path` opened for reading once CheckInputFile accepts it; throws InputError as it does, or
/// when it cannot be opened.
std::ifstream OpenInputFile(const std::string& path, const std::string& what,
                            std::uintmax_t max_bytes = kAnyFileSize,
                            const std::string& budget = "");

/// `megabytes` (a limits.*_mb setting) in bytes.
std::uintmax_t MegabytesToBytes(double megabytes);

/// OpenInputFile for a text input read whole (a TUM trajectory, a text log, a g2o graph, a
/// CSV, waypoints): at most `max_mb` MiB, the setting limits.max_input_file_mb.
std::ifstream OpenTextInput(const std::string& path, const std::string& what, double max_mb);

/// The contents of `path`. Throws InputError as CheckInputFile does, and when it cannot be
/// read or grows past `max_bytes` while it is read.
std::string ReadBoundedFile(const std::string& path, const std::string& what,
                            std::uintmax_t max_bytes = kMaxYamlFileBytes);

}  // namespace uwbsar
