// Simulated wheel odometry of a differential-drive base (Kobuki-like). The true
// wheel travel between two steps follows from the true motion; the encoders
// measure it with systematic errors (wheel radii not what the base assumes,
// left and right unequal, wheelbase not what the base assumes) and random
// slip, quantised to ticks; the base integrates the ticks with its nominal
// geometry (midpoint rule), as a real base driver does. The result drifts like
// real odometry: about wheel_scale_error in distance, and heading drift from
// the left/right asymmetry (straight driving) and the wheelbase error (turns).
#pragma once

#include <cstdint>
#include <random>

#include "core/types.h"
#include "drivers/sim/simulator_config.h"
#include "drivers/sim/trajectory.h"

namespace uwbsar::sim {

class WheelOdometrySimulator {
 public:
  /// Odometry starts at the true pose `start` (odometry frame = world frame at t = 0).
  WheelOdometrySimulator(const SimOdometryConfig& config, const RobotState& start,
                         std::uint64_t seed);

  /// Advances to the true state `truth` at `stamp_ns` (calls in time order) and returns
  /// the base's odometry: integrated pose and the velocities of the last step.
  OdometrySample Step(TimestampNs stamp_ns, const RobotState& truth);

  /// The distance the base measured over the last step (mean of both wheels), m.
  double last_distance_m() const { return last_distance_m_; }

 private:
  SimOdometryConfig config_;
  std::mt19937_64 rng_;
  std::normal_distribution<double> slip_;
  RobotState last_truth_;
  TimestampNs last_stamp_ns_ = 0;
  bool started_ = false;
  double wheel_travel_m_[2] = {0.0, 0.0};  ///< measured travel (left, right), before ticks
  std::int64_t ticks_[2] = {0, 0};
  Pose2 pose_;
  double last_distance_m_ = 0.0;
};

}  // namespace uwbsar::sim
