#include "drivers/rosbag/cdr_writer.h"

#include <cassert>
#include <limits>

namespace uwbsar::rosbag {

namespace {
constexpr std::size_t kHeaderBytes = 4;
}

CdrWriter::CdrWriter(std::vector<std::uint8_t>* out) : out_(out) {
  out_->assign({0x00, 0x01, 0x00, 0x00});
}

void CdrWriter::Align(std::size_t n) {
  const std::size_t pos = out_->size() - kHeaderBytes;
  const std::size_t pad = (n - pos % n) % n;
  out_->resize(out_->size() + pad, 0);
}

void CdrWriter::WriteString(const std::string& s) {
  Write(static_cast<std::uint32_t>(s.size() + 1));
  out_->insert(out_->end(), s.begin(), s.end());
  out_->push_back(0);
}

void CdrWriter::WriteSequenceLength(std::size_t n) {
  assert(n <= std::numeric_limits<std::uint32_t>::max());
  Write(static_cast<std::uint32_t>(n));
}

}  // namespace uwbsar::rosbag
