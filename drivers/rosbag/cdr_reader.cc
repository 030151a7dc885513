#include "drivers/rosbag/cdr_reader.h"

#include <cstdio>

namespace uwbsar::rosbag {

CdrReader::CdrReader(const std::uint8_t* data, std::size_t size) : data_(data), size_(0) {
  if (size < 4) {
    throw InputError("CDR payload of " + std::to_string(size) +
                     " bytes is shorter than the 4-byte encapsulation header");
  }
  const unsigned kind = (static_cast<unsigned>(data[0]) << 8) | data[1];
  if (kind != 0x0001) {
    char hex[16];
    std::snprintf(hex, sizeof(hex), "%02x %02x", data[0], data[1]);
    const char* name = kind == 0x0000                     ? "big-endian CDR"
                       : kind == 0x0002                   ? "big-endian parameter-list CDR"
                       : kind == 0x0003                   ? "parameter-list CDR"
                       : kind >= 0x0006 && kind <= 0x000b ? "XCDR2"
                                                          : "unknown";
    throw InputError(std::string("CDR encapsulation ") + hex + " (" + name +
                     ") is not supported; expected 00 01 (little-endian XCDR1)");
  }
  data_ = data + 4;
  size_ = size - 4;
}

void CdrReader::Align(std::size_t n) {
  const std::size_t pad = (n - pos_ % n) % n;
  if (pad > Remaining()) Need(pad, "alignment padding");
  pos_ += pad;
}

void CdrReader::Need(std::size_t n, const char* what) const {
  if (n <= Remaining()) return;
  throw InputError("CDR " + std::string(what) + " of " + std::to_string(n) +
                   " bytes at payload offset " + std::to_string(pos_) + " overruns the " +
                   std::to_string(size_) + "-byte payload");
}

std::string CdrReader::ReadString() {
  const std::size_t at = Offset();
  const auto length = Read<std::uint32_t>();
  if (length == 0) return {};  // some writers emit 0 for an empty string
  Need(length, "string");
  const char* p = reinterpret_cast<const char*>(data_ + pos_);
  if (p[length - 1] != '\0') {
    throw InputError("CDR string at payload offset " + std::to_string(at) +
                     " is not NUL-terminated");
  }
  pos_ += length;
  return std::string(p, length - 1);
}

std::size_t CdrReader::ReadSequenceLength(std::size_t element_min_bytes) {
  const std::size_t at = Offset();
  const std::size_t n = Read<std::uint32_t>();
  if (element_min_bytes > 0 && n > Remaining() / element_min_bytes) {
    throw InputError("CDR sequence length " + std::to_string(n) + " at payload offset " +
                     std::to_string(at) + " overruns the " + std::to_string(size_) +
                     "-byte payload");
  }
  return n;
}

void CdrReader::ExpectEnd() const {
  if (Remaining() > 3) {
    throw InputError("CDR payload has " + std::to_string(Remaining()) +
                     " unread bytes after offset " + std::to_string(pos_) +
                     " (not the message type it was decoded as?)");
  }
}

}  // namespace uwbsar::rosbag
