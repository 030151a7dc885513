// Writing one ROS 2 message as little-endian XCDR1 (the inverse of CdrReader):
// encapsulation header `00 01 00 00`, then primitives aligned to their size
// relative to the byte after the header, zero padding.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

namespace uwbsar::rosbag {

class CdrWriter {
 public:
  /// Clears `out` and writes the encapsulation header into it.
  explicit CdrWriter(std::vector<std::uint8_t>* out);

  template <class T>
  void Write(T v) {
    static_assert(std::is_arithmetic_v<T>, "primitives only");
    Align(sizeof(T));
    const std::size_t at = out_->size();
    out_->resize(at + sizeof(T));
    std::memcpy(out_->data() + at, &v, sizeof(T));
  }
  void WriteString(const std::string& s);
  void WriteSequenceLength(std::size_t n);
  template <class T>
  void WriteArray(const T* src, std::size_t n) {
    static_assert(std::is_arithmetic_v<T>, "primitives only");
    if (n == 0) return;
    Align(sizeof(T));
    const std::size_t at = out_->size();
    out_->resize(at + n * sizeof(T));
    std::memcpy(out_->data() + at, src, n * sizeof(T));
  }
  template <class T>
  void WriteSequence(const std::vector<T>& v) {
    WriteSequenceLength(v.size());
    WriteArray(v.data(), v.size());
  }

 private:
  void Align(std::size_t n);
  std::vector<std::uint8_t>* out_;
};

}  // namespace uwbsar::rosbag
