// Reading a small text file (configuration, map_server YAML, bag metadata.yaml) whole,
// with a size cap: a path to /dev/zero, a FIFO or a huge file must give one clear error,
// not fill the memory.
#pragma once

#include <cstdint>
#include <string>

namespace uwbsar {

/// The largest YAML file uwbsar reads (configuration, map YAML, bag metadata).
constexpr std::uintmax_t kMaxYamlFileBytes = 4u << 20;  // 4 MiB

/// The contents of `path`. Throws InputError naming the path and `what` (e.g.
/// "configuration") when it does not exist, cannot be read, is not a regular file
/// (a device, FIFO or folder) or holds more than `max_bytes`.
std::string ReadBoundedFile(const std::string& path, const std::string& what,
                            std::uintmax_t max_bytes = kMaxYamlFileBytes);

}  // namespace uwbsar
