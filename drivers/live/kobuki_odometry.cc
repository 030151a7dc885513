#include "drivers/live/kobuki_odometry.h"

#include <cmath>

namespace uwbsar::live {

std::optional<OdometrySample> KobukiOdometry::Update(TimestampNs stamp_ns,
                                                     const KobukiBasicSensorData& data) {
  if (!started_) {
    started_ = true;
    last_left_ = data.left_encoder;
    last_right_ = data.right_encoder;
    last_stamp_ns_ = stamp_ns;
    return std::nullopt;
  }
  const double metres_per_tick =
      2.0 * M_PI * geometry_.wheel_radius_m / geometry_.ticks_per_revolution;
  const double left_m = TickDelta(last_left_, data.left_encoder) * metres_per_tick;
  const double right_m = TickDelta(last_right_, data.right_encoder) * metres_per_tick;
  const double dt_s = NsToSeconds(stamp_ns - last_stamp_ns_);
  last_left_ = data.left_encoder;
  last_right_ = data.right_encoder;
  // Packets are 20 ms apart; a shorter host interval is jitter, so speed is judged over
  // at least one packet period.
  const double judged_dt_s = std::max(dt_s, 0.02);
  OdometrySample sample;
  sample.stamp_ns = stamp_ns;
  if (std::max(std::abs(left_m), std::abs(right_m)) > geometry_.max_wheel_speed_mps * judged_dt_s) {
    ++jumps_;
  } else {
    const double d = 0.5 * (left_m + right_m);
    const double dyaw = (right_m - left_m) / geometry_.wheelbase_m;
    const double mid = pose_.yaw_rad + 0.5 * dyaw;
    pose_.x_m += d * std::cos(mid);
    pose_.y_m += d * std::sin(mid);
    pose_.yaw_rad = NormalizeAngle(pose_.yaw_rad + dyaw);
    if (dt_s > 0) {
      sample.linear_velocity_mps = d / dt_s;
      sample.angular_velocity_radps = dyaw / dt_s;
    }
  }
  last_stamp_ns_ = stamp_ns;
  sample.T_world_robot = pose_;
  return sample;
}

}  // namespace uwbsar::live
