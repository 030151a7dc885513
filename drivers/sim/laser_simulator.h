// A simulated 2-D LiDAR (like sensor_msgs/LaserScan): one beam per angle step
// over a full turn, each measuring the distance to the first occupied cell of
// the grid, with Gaussian range noise. REP 117 conventions: +inf when nothing
// is within range_max, -inf when the return is closer than range_min.
#pragma once

#include <random>
#include <vector>

#include "core/types.h"
#include "drivers/sim/grid_ray_caster.h"
#include "drivers/sim/simulator_config.h"
#include "drivers/sim/walking_people.h"

namespace uwbsar::sim {

struct SimLaserScan {
  TimestampNs stamp_ns = 0;
  float angle_min_rad = 0.0f;
  float angle_increment_rad = 0.0f;
  float scan_time_s = 0.0f;  ///< time between scans
  float range_min_m = 0.0f;
  float range_max_m = 0.0f;
  std::vector<float> ranges_m;  ///< beam i at angle_min + i * angle_increment (laser frame)
};

/// One scan from a laser at T_world_laser (x forward); noise from `rng` (nullptr: none).
/// `movers` (people walking past, at this instant) stop the beams that meet them first.
SimLaserScan SimulateLaserScan(const GridRayCaster& caster, const Pose2& T_world_laser,
                               const SimLaserConfig& config, std::mt19937_64* rng,
                               const std::vector<SimDisc>& movers = {});

}  // namespace uwbsar::sim
