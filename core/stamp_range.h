// The stamps uwbsar's outputs can hold. results.mcap and simulated bags carry each stamp as a
// ROS 2 time in the messages' headers (builtin_interfaces/Time: int32 seconds, uint32
// nanoseconds) and as an MCAP log time (uint64 nanoseconds since 1970): together they hold
// 1970-01-01T00:00:00Z .. 2038-01-19T03:14:07.999999999Z. A stamp outside would be written
// wrapped (a bag in 2150 as 2014) or out of order (a negative stamp as a log time), so the
// readers of recordings and trajectories refuse it, naming the message or line
// (docs/refusals.md).
#pragma once

#include <string>

#include "core/types.h"

namespace uwbsar {

inline constexpr TimestampNs kFirstOutputStampNs = 0;
inline constexpr TimestampNs kLastOutputStampNs = 2147483647LL * 1000000000LL + 999999999LL;

inline bool IsOutputStamp(TimestampNs stamp_ns) {
  return stamp_ns >= kFirstOutputStampNs && stamp_ns <= kLastOutputStampNs;
}

/// "1970-01-01 00:00:00 .. 2038-01-19 03:14:07 UTC, the times ROS 2 messages (int32 seconds)
/// can hold".
std::string OutputStampRange();

/// Why `stamp_ns` cannot be used, for a message that names where it came from: "stamp
/// 5680281600.000000000 s (2150-01-01 00:00:00 UTC) is outside 1970-01-01 00:00:00 ..
/// 2038-01-19 03:14:07 UTC, the times ROS 2 messages (int32 seconds) can hold".
std::string StampOutsideOutputRange(TimestampNs stamp_ns);

}  // namespace uwbsar
