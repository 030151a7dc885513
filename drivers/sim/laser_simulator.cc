#include "drivers/sim/laser_simulator.h"

#include <cmath>
#include <limits>

namespace uwbsar::sim {

SimLaserScan SimulateLaserScan(const GridRayCaster& caster, const Pose2& T_world_laser,
                               const SimLaserConfig& config, std::mt19937_64* rng,
                               const std::vector<SimDisc>& movers) {
  SimLaserScan scan;
  const double increment = 2.0 * M_PI / config.num_beams;
  scan.angle_min_rad = static_cast<float>(-M_PI);
  scan.angle_increment_rad = static_cast<float>(increment);
  scan.scan_time_s = static_cast<float>(1.0 / config.rate_hz);
  scan.range_min_m = static_cast<float>(config.min_range_m);
  scan.range_max_m = static_cast<float>(config.max_range_m);
  scan.ranges_m.resize(static_cast<std::size_t>(config.num_beams));
  std::normal_distribution<double> noise(0.0, config.noise_std_m > 0 ? config.noise_std_m : 1.0);
  const Point2 origin{T_world_laser.x_m, T_world_laser.y_m};
  for (int i = 0; i < config.num_beams; ++i) {
    const double angle = T_world_laser.yaw_rad - M_PI + i * increment;
    const RayHit hit = caster.FirstHit(origin, angle, config.max_range_m);
    double range = hit.cell >= 0 ? hit.range_m : std::numeric_limits<double>::infinity();
    bool returned = hit.cell >= 0;
    for (const SimDisc& d : movers) {
      const double t = RayDiscDistance(origin, angle, d);
      if (t >= 0 && t < range && t <= config.max_range_m) range = t, returned = true;
    }
    if (returned) {
      if (config.noise_std_m > 0 && rng != nullptr) range += noise(*rng);
      if (range > config.max_range_m) range = std::numeric_limits<double>::infinity();
      if (range < config.min_range_m) range = -std::numeric_limits<double>::infinity();
    }
    scan.ranges_m[i] = static_cast<float>(range);
  }
  return scan;
}

}  // namespace uwbsar::sim
