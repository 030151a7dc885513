#include "drivers/sim/base_odometry.h"

#include <cmath>
#include <stdexcept>

namespace uwbsar::sim {

BaseOdometrySimulator::BaseOdometrySimulator(const SimOdometryConfig& config,
                                             const RobotState& start, std::uint64_t wheel_seed,
                                             std::uint64_t gyro_seed)
    : wheels_(config, start, wheel_seed), last_truth_(start), pose_(start.T_world_robot) {
  if (config.profile == "kobuki_gyro") {
    gyro_.emplace(config.gyro, start.T_world_robot.yaw_rad, gyro_seed);
  } else if (config.profile != "wheel") {
    throw std::invalid_argument("unknown odometry profile '" + config.profile + "'");
  }
}

OdometrySample BaseOdometrySimulator::Step(TimestampNs stamp_ns, const RobotState& truth,
                                           bool carried) {
  const double true_dyaw = truth.heading_rad - last_truth_.heading_rad;
  if (carried) {
    carried_path_m_ += truth.path_m - last_truth_.path_m;
    carried_heading_rad_ += true_dyaw;
  }
  last_truth_ = truth;
  // The wheels roll only where the robot drove: their truth leaves out what it was carried.
  RobotState rolled = truth;
  rolled.path_m -= carried_path_m_;
  rolled.heading_rad -= carried_heading_rad_;
  OdometrySample wheel = wheels_.Step(stamp_ns, rolled);
  if (!gyro_) return wheel;
  const double dt = started_ ? NsToSeconds(stamp_ns - last_stamp_ns_) : 0.0;
  const double yaw = gyro_->Step(dt, true_dyaw);
  // The wheels' distance along the mean of the heading before and after the step (midpoint
  // rule, as the wheel-only integration).
  const double d = wheels_.last_distance_m();
  const double dyaw = yaw - pose_.yaw_rad;
  const double mid = pose_.yaw_rad + 0.5 * dyaw;
  pose_.x_m += d * std::cos(mid);
  pose_.y_m += d * std::sin(mid);
  pose_.yaw_rad = yaw;  // unwrapped here, so the next step's difference is the turn itself
  OdometrySample sample = wheel;
  sample.T_world_robot = {pose_.x_m, pose_.y_m, NormalizeAngle(yaw)};
  sample.angular_velocity_radps = dt > 0 ? dyaw / dt : 0.0;
  started_ = true;
  last_stamp_ns_ = stamp_ns;
  return sample;
}

}  // namespace uwbsar::sim
