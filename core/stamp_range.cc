#include "core/stamp_range.h"

#include <cinttypes>
#include <cstdio>
#include <ctime>

namespace uwbsar {
namespace {

/// "2150-01-01 00:00:00 UTC" of whole seconds since 1970 (any int64 nanosecond stamp's).
std::string UtcDate(std::int64_t sec) {
  const std::time_t t = static_cast<std::time_t>(sec);
  std::tm tm{};
  char date[64] = "?";
  if (gmtime_r(&t, &tm) != nullptr) std::strftime(date, sizeof(date), "%Y-%m-%d %H:%M:%S", &tm);
  return std::string(date) + " UTC";
}

}  // namespace

std::string OutputStampRange() {
  return UtcDate(kFirstOutputStampNs / 1000000000).substr(0, 19) + " .. " +
         UtcDate(kLastOutputStampNs / 1000000000) +
         ", the times ROS 2 messages (int32 seconds) can hold";
}

std::string StampOutsideOutputRange(TimestampNs stamp_ns) {
  // The magnitude unsigned: -INT64_MIN overflows.
  const bool negative = stamp_ns < 0;
  const std::uint64_t magnitude =
      negative ? 0 - static_cast<std::uint64_t>(stamp_ns) : static_cast<std::uint64_t>(stamp_ns);
  char buf[64];
  std::snprintf(buf, sizeof(buf), "%s%" PRIu64 ".%09" PRIu64, negative ? "-" : "",
                magnitude / 1000000000, magnitude % 1000000000);
  // The date of the second holding the stamp (floor division).
  const std::int64_t sec = stamp_ns / 1000000000 - (stamp_ns % 1000000000 < 0 ? 1 : 0);
  return std::string("stamp ") + buf + " s (" + UtcDate(sec) + ") is outside " + OutputStampRange();
}

}  // namespace uwbsar
