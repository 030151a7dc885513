// Helpers of the MCAP storage tests (mcap_storage_test.cc, mcap_recovery_test.cc): files
// written by our writer, read back whole, records located, errors caught.
#pragma once

#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "core/errors.h"
#include "core/log.h"
#include "drivers/rosbag/bag_storage.h"
#include "drivers/rosbag/mcap_format.h"
#include "drivers/rosbag/mcap_storage_reader.h"
#include "test/drivers/bag_test_util.h"

namespace uwbsar::rosbag::testing {

using Bytes = std::vector<std::uint8_t>;
using mcap::Builder;

inline Bytes Payload(int i) {
  Bytes b(4 + static_cast<std::size_t>(i % 50));
  for (std::size_t k = 0; k < b.size(); ++k) b[k] = static_cast<std::uint8_t>(i * 7 + k);
  return b;
}

// Writes `times.size()` messages alternating over two topics.
inline Bytes WriteMcap(const std::string& dir, const McapWriteOptions& options,
                       const std::vector<TimestampNs>& times) {
  const std::string path = dir + "/test.mcap";
  auto w = CreateMcapStorage(path, options);
  TopicInfo a, b;
  a.name = "/a";
  a.type = "std_msgs/msg/Float32MultiArray";
  b.name = "/b";
  b.type = "nav_msgs/msg/Odometry";
  w->AddTopic(a);
  w->AddTopic(b);
  for (std::size_t i = 0; i < times.size(); ++i) {
    const Bytes p = Payload(static_cast<int>(i));
    w->Write(static_cast<int>(i % 2), times[i], p.data(), p.size());
  }
  w->Close("rosbag2_bagfile_information: {}");
  std::ifstream in(path, std::ios::binary);
  return Bytes(std::istreambuf_iterator<char>(in), {});
}

inline std::vector<TimestampNs> Ramp(int n) {
  std::vector<TimestampNs> t;
  for (int i = 0; i < n; ++i) t.push_back(kT0 + i * 1000);
  return t;
}

struct Read {
  std::vector<TimestampNs> times;
  std::vector<int> topics;
  std::vector<Bytes> payloads;
};

inline Read ReadAll(const Bytes& file, McapOpenReport* report = nullptr) {
  auto r = OpenMcapStorage(MakeMemorySource("mem.mcap", file), report);
  Read out;
  StorageMessage m;
  while (r->Next(&m)) {
    out.times.push_back(m.log_time_ns);
    out.topics.push_back(m.topic);
    out.payloads.emplace_back(m.data, m.data + m.size);
  }
  return out;
}

// Offset of the first record with `opcode` in the data section.
/// Offset of the `nth` (1-based) record with `opcode`, scanning from the magic; 0 if none.
inline std::size_t FindRecord(const Bytes& f, std::uint8_t opcode, int nth = 1) {
  int seen = 0;
  for (std::size_t off = 8; off + 9 <= f.size();) {
    std::uint64_t len;
    std::memcpy(&len, f.data() + off + 1, 8);
    if (f[off] == opcode && ++seen == nth) return off;
    off += 9 + len;
  }
  return 0;
}

inline std::string ErrorOf(const Bytes& file) {
  try {
    ReadAll(file);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

// Silences the recovery warnings of tests that open thousands of damaged files.
struct QuietLog {
  QuietLog() : saved(GetLogLevel()) { SetLogLevel(LogLevel::kSilent); }
  ~QuietLog() { SetLogLevel(saved); }
  LogLevel saved;
};

}  // namespace uwbsar::rosbag::testing
