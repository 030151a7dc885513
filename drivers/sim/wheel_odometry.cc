#include "drivers/sim/wheel_odometry.h"

#include <cmath>

namespace uwbsar::sim {

WheelOdometrySimulator::WheelOdometrySimulator(const SimOdometryConfig& config,
                                               const RobotState& start, std::uint64_t seed)
    : config_(config),
      rng_(seed),
      slip_(0.0, config.wheel_slip_std > 0 ? config.wheel_slip_std : 1.0),
      last_truth_(start),
      pose_(start.T_world_robot) {}

OdometrySample WheelOdometrySimulator::Step(TimestampNs stamp_ns, const RobotState& truth) {
  const double ds = truth.path_m - last_truth_.path_m;
  const double dtheta = truth.heading_rad - last_truth_.heading_rad;
  last_truth_ = truth;
  // True travel of each wheel on the floor, with the true wheelbase.
  const double true_base = config_.wheelbase_m * (1.0 - config_.wheelbase_error);
  const double travel[2] = {ds - 0.5 * dtheta * true_base, ds + 0.5 * dtheta * true_base};
  const double scale[2] = {1.0 + config_.wheel_scale_error - 0.5 * config_.wheel_scale_asymmetry,
                           1.0 + config_.wheel_scale_error + 0.5 * config_.wheel_scale_asymmetry};
  const double metres_per_tick = 2.0 * M_PI * config_.wheel_radius_m / config_.ticks_per_revolution;
  double measured[2];
  for (int k = 0; k < 2; ++k) {
    double slip = 1.0;
    if (config_.wheel_slip_std > 0 && travel[k] != 0.0) slip += slip_(rng_);
    wheel_travel_m_[k] += travel[k] * scale[k] * slip;
    const auto ticks = static_cast<std::int64_t>(std::floor(wheel_travel_m_[k] / metres_per_tick));
    measured[k] = static_cast<double>(ticks - ticks_[k]) * metres_per_tick;
    ticks_[k] = ticks;
  }
  // The base's integration with its nominal wheelbase (midpoint rule).
  const double d = 0.5 * (measured[0] + measured[1]);
  last_distance_m_ = d;
  const double dyaw = (measured[1] - measured[0]) / config_.wheelbase_m;
  const double mid = pose_.yaw_rad + 0.5 * dyaw;
  pose_.x_m += d * std::cos(mid);
  pose_.y_m += d * std::sin(mid);
  pose_.yaw_rad = NormalizeAngle(pose_.yaw_rad + dyaw);
  OdometrySample sample;
  sample.stamp_ns = stamp_ns;
  sample.T_world_robot = pose_;
  const double dt = started_ ? NsToSeconds(stamp_ns - last_stamp_ns_) : 0.0;
  if (dt > 0) {
    sample.linear_velocity_mps = d / dt;
    sample.angular_velocity_radps = dyaw / dt;
  }
  started_ = true;
  last_stamp_ns_ = stamp_ns;
  return sample;
}

}  // namespace uwbsar::sim
