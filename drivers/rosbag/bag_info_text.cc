#include "drivers/rosbag/bag_info_text.h"

#include <cinttypes>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <sstream>

namespace uwbsar::rosbag {

std::string HumanBytes(std::uint64_t bytes) {
  static const char* const kUnits[] = {"B", "KiB", "MiB", "GiB", "TiB"};
  double v = static_cast<double>(bytes);
  int u = 0;
  while (v >= 1024.0 && u < 4) {
    v /= 1024.0;
    ++u;
  }
  char buf[32];
  if (u == 0) {
    std::snprintf(buf, sizeof(buf), "%" PRIu64 " B", bytes);
  } else {
    std::snprintf(buf, sizeof(buf), "%.1f %s", v, kUnits[u]);
  }
  return buf;
}

std::string FormatBagTime(TimestampNs t) {
  // Floor division without negating t (-INT64_MIN overflows).
  std::int64_t sec = t / 1000000000;
  if (t % 1000000000 < 0) --sec;
  const auto nsec = static_cast<long>(t - sec * 1000000000);
  const std::time_t tt = static_cast<std::time_t>(sec);
  std::tm tm{};
  localtime_r(&tt, &tm);
  char date[64];
  std::strftime(date, sizeof(date), "%b %e %Y %H:%M:%S", &tm);
  char buf[128];
  std::snprintf(buf, sizeof(buf), "%s.%09ld (%" PRId64 ".%09ld)", date, nsec, sec, nsec);
  return buf;
}

std::string FormatBagInfo(const BagInfo& info) {
  std::ostringstream out;
  const auto line = [&out](const char* key, const std::string& value) {
    char buf[32];
    std::snprintf(buf, sizeof(buf), "%-19s", key);
    out << buf << value << "\n";
  };
  std::string files;
  for (std::size_t i = 0; i < info.files.size(); ++i) {
    if (i > 0) files += "\n" + std::string(19, ' ');
    files += std::filesystem::path(info.files[i]).filename().string();
  }
  line("Files:", files);
  line("Bag size:", HumanBytes(info.size_bytes));
  line("Storage id:", info.storage_identifier);
  if (info.metadata_version > 0) {
    line("Metadata version:", std::to_string(info.metadata_version));
  } else {
    line("Metadata:", "none (bare storage file; counts from the file)");
  }
  if (!info.compression_mode.empty()) {
    line("Compression:", info.compression_format + " (" + info.compression_mode + ")");
  }
  char duration[64];
  const std::int64_t d = info.duration_ns();
  std::snprintf(duration, sizeof(duration), "%" PRId64 ".%09" PRId64 "s", d / 1000000000,
                d % 1000000000);
  line("Duration:", duration);
  line("Start:", FormatBagTime(info.start_ns));
  line("End:", FormatBagTime(info.end_ns));
  line("Messages:", std::to_string(info.message_count));
  std::string topics;
  for (std::size_t i = 0; i < info.topics.size(); ++i) {
    const TopicInfo& t = info.topics[i];
    if (i > 0) topics += "\n" + std::string(19, ' ');
    topics += "Topic: " + t.name + " | Type: " + t.type +
              " | Count: " + std::to_string(t.message_count) +
              " | Serialization Format: " + t.serialization_format;
  }
  line("Topic information:", topics);
  return out.str();
}

}  // namespace uwbsar::rosbag
