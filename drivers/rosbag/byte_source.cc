#include "drivers/rosbag/byte_source.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "core/errors.h"

namespace uwbsar::rosbag {
namespace {

[[noreturn]] void ThrowOutOfRange(const std::string& name, std::uint64_t offset, std::size_t size,
                                  std::uint64_t total) {
  throw InputError(name + ": truncated or corrupt: needs " + std::to_string(size) +
                   " bytes at offset " + std::to_string(offset) + " but the file has " +
                   std::to_string(total) + " bytes");
}

class FileSource final : public ByteSource {
 public:
  FileSource(std::string path, int fd, std::uint64_t size)
      : path_(std::move(path)), fd_(fd), size_(size) {}
  ~FileSource() override { ::close(fd_); }
  FileSource(const FileSource&) = delete;
  FileSource& operator=(const FileSource&) = delete;

  const std::string& Name() const override { return path_; }
  std::uint64_t Size() const override { return size_; }
  void ReadAt(std::uint64_t offset, std::size_t size, void* dst) const override {
    if (offset > size_ || size > size_ - offset) ThrowOutOfRange(path_, offset, size, size_);
    auto* out = static_cast<char*>(dst);
    std::size_t done = 0;
    while (done < size) {
      const ssize_t n = ::pread(fd_, out + done, size - done, static_cast<off_t>(offset + done));
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) {
        throw InputError(
            path_ + ": read failed at offset " + std::to_string(offset + done) + ": " +
            (n == 0 ? std::string("unexpected end of file") : std::string(std::strerror(errno))));
      }
      done += static_cast<std::size_t>(n);
    }
  }

 private:
  std::string path_;
  int fd_;
  std::uint64_t size_;
};

class MemorySource final : public ByteSource {
 public:
  MemorySource(std::string name, std::vector<std::uint8_t> bytes)
      : name_(std::move(name)), bytes_(std::move(bytes)) {}
  const std::string& Name() const override { return name_; }
  std::uint64_t Size() const override { return bytes_.size(); }
  void ReadAt(std::uint64_t offset, std::size_t size, void* dst) const override {
    if (offset > bytes_.size() || size > bytes_.size() - offset) {
      ThrowOutOfRange(name_, offset, size, bytes_.size());
    }
    if (size > 0) std::memcpy(dst, bytes_.data() + offset, size);
  }

 private:
  std::string name_;
  std::vector<std::uint8_t> bytes_;
};

}  // namespace

std::unique_ptr<ByteSource> OpenFileSource(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw InputError(path + ": cannot open: " + std::strerror(errno));
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd);
    throw InputError(path + ": not a regular file");
  }
  return std::make_unique<FileSource>(path, fd, static_cast<std::uint64_t>(st.st_size));
}

std::unique_ptr<ByteSource> MakeMemorySource(std::string name, std::vector<std::uint8_t> bytes) {
  return std::make_unique<MemorySource>(std::move(name), std::move(bytes));
}

}  // namespace uwbsar::rosbag
