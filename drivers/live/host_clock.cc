#include "drivers/live/host_clock.h"

namespace uwbsar::live {
namespace {
std::chrono::nanoseconds SystemMinusSteady() {
  const auto system = std::chrono::system_clock::now().time_since_epoch();
  const auto steady = std::chrono::steady_clock::now().time_since_epoch();
  return std::chrono::duration_cast<std::chrono::nanoseconds>(system) -
         std::chrono::duration_cast<std::chrono::nanoseconds>(steady);
}
}  // namespace

HostClock::HostClock(double scale)
    : scale_(scale),
      epoch0_ns_(std::chrono::duration_cast<std::chrono::nanoseconds>(
                     std::chrono::system_clock::now().time_since_epoch())
                     .count()),
      steady0_(std::chrono::steady_clock::now()),
      offset_(SystemMinusSteady()) {}

TimestampNs HostClock::Now() {
  const auto elapsed = std::chrono::duration_cast<std::chrono::nanoseconds>(
                           std::chrono::steady_clock::now() - steady0_)
                           .count();
  const auto t = epoch0_ns_ + static_cast<TimestampNs>(static_cast<double>(elapsed) * scale_);
  std::lock_guard<std::mutex> lock(mutex_);
  last_ns_ = std::max(t, last_ns_ + 1);
  return last_ns_;
}

double HostClock::CheckStep() {
  const auto now = SystemMinusSteady();
  std::lock_guard<std::mutex> lock(mutex_);
  const double step_s = std::chrono::duration<double>(now - offset_).count();
  offset_ = now;
  return step_s;
}

}  // namespace uwbsar::live
