// Wheel odometry of a differential-drive base from its encoder ticks: the tick
// differences since the last packet (16-bit counters, wrap-around taken as the
// shortest signed difference) times the metres per tick, integrated with the
// configured wheelbase by the midpoint rule. A step whose wheel speed exceeds the
// configured maximum is a jump (a reset base, a corrupted packet that passed the
// checksum): it is not integrated, only counted, so the pose stays continuous.
#pragma once

#include <optional>

#include "core/types.h"
#include "drivers/live/kobuki_protocol.h"

namespace uwbsar::live {

struct KobukiGeometry {
  double wheel_radius_m = 0.035;
  double wheelbase_m = 0.230;
  double ticks_per_revolution = 2578.33;
  double max_wheel_speed_mps = 1.0;
};

class KobukiOdometry {
 public:
  explicit KobukiOdometry(const KobukiGeometry& geometry) : geometry_(geometry) {}

  /// The odometry after a packet received at `stamp_ns` (host clock); nullopt for the
  /// very first packet, which only sets the tick reference.
  std::optional<OdometrySample> Update(TimestampNs stamp_ns, const KobukiBasicSensorData& data);

  long long jumps() const { return jumps_; }
  const Pose2& pose() const { return pose_; }

 private:
  KobukiGeometry geometry_;
  bool started_ = false;
  std::uint16_t last_left_ = 0, last_right_ = 0;
  TimestampNs last_stamp_ns_ = 0;
  Pose2 pose_;
  long long jumps_ = 0;
};

/// The signed difference b - a of two 16-bit counters across a wrap-around.
inline int TickDelta(std::uint16_t a, std::uint16_t b) {
  return static_cast<int>(static_cast<std::int16_t>(static_cast<std::uint16_t>(b - a)));
}

}  // namespace uwbsar::live
