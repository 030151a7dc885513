// The messages that flow from drivers to the frontend (docs/architecture.md "Data flow").
#pragma once

#include <cstdint>
#include <vector>

#include "core/pose2.h"

namespace uwbsar {

/// Nanoseconds since the Unix epoch (ROS 2 convention for bag timestamps).
using TimestampNs = std::int64_t;

inline double NsToSeconds(TimestampNs t) { return static_cast<double>(t) * 1e-9; }
inline TimestampNs SecondsToNs(double s) { return static_cast<TimestampNs>(std::llround(s * 1e9)); }

/// One raw radar scan: real-valued samples, sample k at range k * bin + range offset.
struct RadarScan {
  TimestampNs stamp_ns = 0;
  int sensor_id = 0;  ///< index into Config::radars
  std::vector<float> samples;
};

/// One wheel-odometry sample: pose of the robot in the odometry (world) frame.
struct OdometrySample {
  TimestampNs stamp_ns = 0;
  Pose2 T_world_robot;
  double linear_velocity_mps = 0.0;
  double angular_velocity_radps = 0.0;
};

}  // namespace uwbsar
