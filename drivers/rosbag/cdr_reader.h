// Reading one serialized ROS 2 message: OMG CDR (XCDR1), little-endian, as every
// ROS 2 RMW writes it on x86/ARM. The first 4 bytes are the encapsulation header
// `00 01 00 00`; an n-byte primitive is aligned to n (at most 8) relative to the byte
// after that header. Every read is bounds-checked: malformed bytes throw
// InputError("CDR ...: what, at payload offset N"), never read out of range.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

#include "core/errors.h"

namespace uwbsar::rosbag {

class CdrReader {
 public:
  /// Checks the encapsulation header; throws InputError for big-endian, XCDR2 or
  /// parameter-list encodings and for payloads shorter than the header.
  CdrReader(const std::uint8_t* data, std::size_t size);

  template <class T>
  T Read() {
    static_assert(std::is_arithmetic_v<T>, "primitives only");
    Align(sizeof(T));
    Need(sizeof(T), "primitive");
    T v;
    std::memcpy(&v, data_ + pos_, sizeof(T));
    pos_ += sizeof(T);
    return v;
  }
  /// A string: u32 length including the NUL, the bytes, the NUL.
  std::string ReadString();
  /// A sequence count, checked against the bytes left for `element_min_bytes` each.
  std::size_t ReadSequenceLength(std::size_t element_min_bytes);
  /// `n` consecutive primitives (a fixed array or a sequence body) in one copy.
  template <class T>
  void ReadArray(T* dst, std::size_t n) {
    static_assert(std::is_arithmetic_v<T>, "primitives only");
    if (n == 0) return;
    Align(sizeof(T));
    if (n > Remaining() / sizeof(T)) Need(n * sizeof(T), "array");
    std::memcpy(dst, data_ + pos_, n * sizeof(T));
    pos_ += n * sizeof(T);
  }
  /// A sequence of primitives into `out` (resized).
  template <class T>
  void ReadSequence(std::vector<T>* out) {
    const std::size_t n = ReadSequenceLength(sizeof(T));
    out->resize(n);
    ReadArray(out->data(), n);
  }
  /// Throws unless at most 3 padding bytes are left: more means the bytes are not
  /// the type they were decoded as.
  void ExpectEnd() const;

  /// Offset in the payload (after the encapsulation header).
  std::size_t Offset() const { return pos_; }
  std::size_t Remaining() const { return size_ - pos_; }

 private:
  void Align(std::size_t n);
  void Need(std::size_t n, const char* what) const;

  const std::uint8_t* data_;  // payload after the encapsulation header
  std::size_t size_;
  std::size_t pos_ = 0;
};

}  // namespace uwbsar::rosbag
