// The clock that stamps live messages: nanoseconds since the epoch, taken from the
// system clock once at start and advanced by the monotonic clock, so an NTP or
// manual clock step cannot send stamps backwards or jump the SLAM timeline. Steps
// of the system clock against the monotonic one are detected and counted.
// `scale` > 1 runs the stamps faster than wall time (tests replaying faster than
// real time: device emulators and this clock share the same scale).
#pragma once

#include <chrono>
#include <mutex>

#include "core/types.h"

namespace uwbsar::live {

class HostClock {
 public:
  explicit HostClock(double scale = 1.0);
  /// Monotonic stamp; strictly increasing across calls from any thread.
  TimestampNs Now();
  /// Seconds the system clock moved against the monotonic clock since the last check
  /// (0 when it did not); re-baselines so one step is reported once.
  double CheckStep();
  double scale() const { return scale_; }

 private:
  double scale_;
  TimestampNs epoch0_ns_;
  std::chrono::steady_clock::time_point steady0_;
  TimestampNs last_ns_ = 0;
  std::chrono::nanoseconds offset_;  ///< system - steady at the last check
  std::mutex mutex_;
};

}  // namespace uwbsar::live
