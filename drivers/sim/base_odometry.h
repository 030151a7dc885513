// The odometry the simulated base publishes on /odom, by profile
// (simulator.odometry.profile):
//  - wheel: the wheel encoders alone (drivers/sim/wheel_odometry.h), heading included;
//  - kobuki_gyro: the heading from the base's gyro (drivers/sim/gyro_model.h) and the distance
//    from the wheels, laid along that heading, as kobuki_node publishes /odom by default
//    (use_imu_heading: the pose's yaw is the gyro's angle, the wheels give the translation).
// Both profiles draw the wheels' slip from the same generator, so a seed gives the same wheel
// errors under either; the gyro has its own generator.
#pragma once

#include <cstdint>
#include <optional>

#include "core/types.h"
#include "drivers/sim/gyro_model.h"
#include "drivers/sim/simulator_config.h"
#include "drivers/sim/trajectory.h"
#include "drivers/sim/wheel_odometry.h"

namespace uwbsar::sim {

class BaseOdometrySimulator {
 public:
  /// `wheel_seed` drives the wheel slip, `gyro_seed` the gyro (kobuki_gyro only). Throws
  /// std::invalid_argument for an unknown profile (configurations are validated before).
  BaseOdometrySimulator(const SimOdometryConfig& config, const RobotState& start,
                        std::uint64_t wheel_seed, std::uint64_t gyro_seed);

  /// Advances to the true state `truth` at `stamp_ns` (calls in time order) and returns the
  /// base's odometry: integrated pose and the velocities of the last step. `carried`: the robot
  /// was carried, wheels off the ground, since the last step (simulator.carried): the wheels
  /// measure nothing of it, a gyro still measures its turn.
  OdometrySample Step(TimestampNs stamp_ns, const RobotState& truth, bool carried = false);

  /// The gyro, with the kobuki_gyro profile; nullptr with wheel.
  const GyroModel* gyro() const { return gyro_ ? &*gyro_ : nullptr; }

 private:
  WheelOdometrySimulator wheels_;
  std::optional<GyroModel> gyro_;
  RobotState last_truth_;
  double carried_path_m_ = 0.0;       ///< true path and ...
  double carried_heading_rad_ = 0.0;  ///< ... turn while carried: the wheels never saw them
  TimestampNs last_stamp_ns_ = 0;
  bool started_ = false;
  Pose2 pose_;
};

}  // namespace uwbsar::sim
