// libFuzzer target: the rosbag2 metadata.yaml parser on arbitrary text. Contract under
// test: bad input (syntax, wrong shape, complex keys, wrong types, times that overflow)
// throws InputError naming the file; no other exception escapes and nothing crashes, and
// what is accepted adds up (starting_time + duration does not overflow).
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>

#include "core/errors.h"
#include "drivers/rosbag/bag_metadata.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const uwbsar::rosbag::BagMetadata m = uwbsar::rosbag::ParseBagMetadata(text, "fuzz.yaml");
    if (m.duration_ns < 0 || m.starting_time_ns < 0 ||
        m.duration_ns > std::numeric_limits<std::int64_t>::max() - m.starting_time_ns) {
      __builtin_trap();
    }
  } catch (const uwbsar::InputError& e) {
    if (std::string(e.what()).rfind("fuzz.yaml", 0) != 0) __builtin_trap();  // names the file
  }
  return 0;
}
