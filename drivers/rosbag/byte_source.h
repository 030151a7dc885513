// Random access to the bytes of one storage file. The MCAP parser reads through
// this interface so that the same code serves files on disk (pread, no mmap, so a
// file that shrinks under us is an error, not a SIGBUS) and in-memory buffers
// (tests, fuzzing).
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace uwbsar::rosbag {

class ByteSource {
 public:
  virtual ~ByteSource() = default;
  /// Name used in error messages (the file path).
  virtual const std::string& Name() const = 0;
  virtual std::uint64_t Size() const = 0;
  /// Copies exactly `size` bytes at `offset` into `dst`; throws InputError naming the
  /// source and offset if the range is outside the data or cannot be read.
  virtual void ReadAt(std::uint64_t offset, std::size_t size, void* dst) const = 0;
};

/// Opens `path` for reading; throws InputError if it cannot.
std::unique_ptr<ByteSource> OpenFileSource(const std::string& path);
/// Wraps a copy of `bytes`; `name` stands for the file in messages.
std::unique_ptr<ByteSource> MakeMemorySource(std::string name, std::vector<std::uint8_t> bytes);

}  // namespace uwbsar::rosbag
