// A scripted run for imaging tests, benchmarks and the imaging demo: the robot
// drives a straight line or a constant-radius arc at constant speed with exact
// odometry, and every radar observes a list of point scatterers through the
// EchoSimulator. (The full environment simulator with occupancy grids, ray
// casting and odometry drift builds on this.)
#pragma once

#include <cstdint>
#include <vector>

#include "core/radar_config.h"
#include "core/types.h"
#include "drivers/sim/echo_simulator.h"
#include "imaging/pulse_config.h"

namespace uwbsar {

struct SyntheticPath {
  Pose2 start;  ///< T_world_robot at t = 0
  double length_m = 3.0;
  double speed_mps = 0.2;
  double turn_radius_m = 0.0;  ///< 0 = straight; > 0 turns left, < 0 turns right
  double odometry_rate_hz = 50.0;
  double radar_rate_hz = 100.0;
  TimestampNs start_stamp_ns = 1'700'000'000'000'000'000;
};

struct SyntheticRun {
  std::vector<OdometrySample> odometry;  ///< exact (ground truth) poses
  std::vector<RadarScan> scans;          ///< all radars, time-ordered
};

/// Pose along the path after travelling `s_m`.
Pose2 PathPose(const SyntheticPath& path, double s_m);

/// Scans of every radar along `path`, echoing `scatterers`, with odometry covering them.
SyntheticRun SimulateRun(const PulseConfig& pulse, const std::vector<RadarConfig>& radars,
                         const SyntheticPath& path, const std::vector<Scatterer>& scatterers,
                         const EchoModel& model, std::uint64_t seed);
/// The same with the pulse and radars of any configuration holding them.
template <class Config>
SyntheticRun SimulateRun(const Config& config, const SyntheticPath& path,
                         const std::vector<Scatterer>& scatterers, const EchoModel& model,
                         std::uint64_t seed) {
  return SimulateRun(config.pulse, config.radars, path, scatterers, model, seed);
}

/// Scatterers every `spacing_m` along the segment a-b (a flat wall seen edge-on).
std::vector<Scatterer> WallScatterers(Point2 a, Point2 b, double spacing_m, double amplitude);

}  // namespace uwbsar
