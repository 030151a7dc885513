// libFuzzer target: the MCAP storage reader (footer, summary, record scan, crash
// recovery of files without a footer, chunk decompression none/zstd/lz4, CRCs, k-way
// chunk merge) on arbitrary bytes. Contract under test: bad input throws InputError
// or is recovered up to the first damaged record; nothing else happens, and the
// messages that come out are in time order (and as many as recovery reported); the same
// holds when damaged chunks are skipped (--skip-damaged).
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/errors.h"
#include "core/log.h"
#include "drivers/rosbag/mcap_storage_reader.h"

namespace {

// One pass over the file; `skip` reads as `uwbsar map --skip-damaged` does.
void ReadAll(const std::uint8_t* data, std::size_t size, bool skip) {
  using namespace uwbsar::rosbag;
  try {
    McapOpenReport report;
    BagReadOptions options;
    options.skip_damaged_chunks = skip;
    auto reader =
        OpenMcapStorage(MakeMemorySource("fuzz.mcap", {data, data + size}), &report, options);
    reader->Stats();
    const std::size_t topics = reader->Topics().size();
    StorageMessage m;
    long long last = -1;
    bool first = true;
    std::uint64_t count = 0;
    while (reader->Next(&m)) {
      if (m.topic < 0 || static_cast<std::size_t>(m.topic) >= topics) __builtin_trap();
      if (!first && m.log_time_ns < last) __builtin_trap();
      if (m.size > 0 && (m.data[0] | m.data[m.size - 1]) == 0x100) __builtin_trap();  // touch
      last = m.log_time_ns;
      first = false;
      ++count;
    }
    if (report.recovered && count != report.recovered_messages) __builtin_trap();
  } catch (const uwbsar::InputError&) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  uwbsar::SetLogLevel(uwbsar::LogLevel::kSilent);  // recovery warnings on most inputs
  ReadAll(data, size, false);
  ReadAll(data, size, true);
  return 0;
}
