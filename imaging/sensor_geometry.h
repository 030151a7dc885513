// Radar geometry in the robot frame and the bounds of what it images.
#pragma once

#include "core/pose2.h"
#include "core/radar_config.h"
#include "imaging/pulse_config.h"

namespace uwbsar {

/// The annular field-of-view sector of one radar, in radians and metres.
struct SensorGeometry {
  Pose2 T_robot_sensor;  ///< antenna position, x along boresight
  double fov_half_angle_rad = 0.0;
  double min_range_m = 0.0;
  double max_range_m = 0.0;
  double range_offset_m = 0.0;  ///< range of sample 0
  double bin_size_m = 0.0;      ///< c / (2 fs)
  int num_samples = 0;
  int zero_leading_samples = 0;

  static SensorGeometry FromConfig(const RadarConfig& radar, const PulseConfig& pulse);

  /// Axis-aligned bounds [x_min, x_max, y_min, y_max] of the FOV sector in the robot frame.
  void SectorBoundsInRobot(double bounds[4]) const;
};

}  // namespace uwbsar
