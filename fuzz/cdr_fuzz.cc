// libFuzzer target: the CDR decoders of every message type on arbitrary bytes.
// Contract under test: malformed input throws InputError; nothing else happens
// (no crash, no out-of-bounds read, no huge allocation, no hang). A decoded message
// re-encodes to bytes that decode to the same message.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/errors.h"
#include "drivers/rosbag/ros_codecs.h"

namespace {

using namespace uwbsar::rosbag;

template <class Message>
void Check(const std::uint8_t* data, std::size_t size) {
  Message m;
  try {
    DecodeCdr(data, size, &m);
  } catch (const uwbsar::InputError&) {
    return;
  }
  std::vector<std::uint8_t> again;
  EncodeCdr(m, &again);
  Message m2;
  DecodeCdr(again.data(), again.size(), &m2);  // must not throw: our own encoding
  std::vector<std::uint8_t> third;
  EncodeCdr(m2, &third);
  if (third != again) __builtin_trap();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  Check<Float32MultiArray>(data, size);
  Check<Odometry>(data, size);
  Check<LaserScan>(data, size);
  Check<TfMessage>(data, size);
  return 0;
}
