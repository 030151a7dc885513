#include "drivers/sim/synthetic_run.h"

#include <algorithm>
#include <cmath>

namespace uwbsar {

Pose2 PathPose(const SyntheticPath& path, double s_m) {
  if (path.turn_radius_m == 0.0) return path.start * Pose2{s_m, 0.0, 0.0};
  const double r = path.turn_radius_m;
  const double yaw = s_m / r;
  return path.start * Pose2{r * std::sin(yaw), r * (1.0 - std::cos(yaw)), yaw};
}

SyntheticRun SimulateRun(const PulseConfig& pulse, const std::vector<RadarConfig>& radars,
                         const SyntheticPath& path, const std::vector<Scatterer>& scatterers,
                         const EchoModel& model, std::uint64_t seed) {
  SyntheticRun run;
  std::mt19937_64 rng(seed);
  const double duration_s = path.length_m / path.speed_mps;
  auto stamp = [&](double t) { return path.start_stamp_ns + SecondsToNs(t); };
  const double angular = path.turn_radius_m == 0.0 ? 0.0 : path.speed_mps / path.turn_radius_m;
  // Odometry covers the scans at both ends so every scan can be interpolated.
  const int odom_count = static_cast<int>(std::ceil(duration_s * path.odometry_rate_hz)) + 1;
  for (int i = 0; i <= odom_count; ++i) {
    const double t = i / path.odometry_rate_hz;
    const double s = std::min(t, duration_s) * path.speed_mps;
    run.odometry.push_back({stamp(t), PathPose(path, s), path.speed_mps, angular});
  }
  std::vector<EchoSimulator> sims;
  std::vector<SensorGeometry> sensors;
  for (const RadarConfig& radar : radars) {
    sensors.push_back(SensorGeometry::FromConfig(radar, pulse));
    sims.emplace_back(pulse, sensors.back(), model);
  }
  const int scan_count = static_cast<int>(std::floor(duration_s * path.radar_rate_hz));
  for (int i = 0; i <= scan_count; ++i) {
    const double t = i / path.radar_rate_hz;
    const Pose2 T_world_robot = PathPose(path, t * path.speed_mps);
    for (std::size_t k = 0; k < sims.size(); ++k) {
      RadarScan scan;
      scan.stamp_ns = stamp(t);
      scan.sensor_id = static_cast<int>(k);
      scan.samples = sims[k].Simulate(T_world_robot * sensors[k].T_robot_sensor, scatterers, &rng);
      run.scans.push_back(std::move(scan));
    }
  }
  return run;
}

std::vector<Scatterer> WallScatterers(Point2 a, Point2 b, double spacing_m, double amplitude) {
  std::vector<Scatterer> out;
  const double length = std::hypot(b.x_m - a.x_m, b.y_m - a.y_m);
  const int n = std::max(1, static_cast<int>(std::floor(length / spacing_m)));
  for (int i = 0; i <= n; ++i) {
    const double t = static_cast<double>(i) / n;
    out.push_back({{a.x_m + t * (b.x_m - a.x_m), a.y_m + t * (b.y_m - a.y_m)}, amplitude});
  }
  return out;
}

}  // namespace uwbsar
