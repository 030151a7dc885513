// One simulated UWB radar in a SimEnvironment. A scan is the sum of
//  - an echo of every scatterer in the occupied cells the antenna lights (ray
//    casting: the first occupied surface along each ray of the sector, plus a
//    penetration depth; what is behind it is occluded) and of every visible
//    point target: the transmitted pulse at delay 2R/c, scaled by the
//    scatterer's reflection coefficient, the two-way Gaussian beam pattern
//    (-3 dB at beam_3db_half_angle_deg) and 1/R^2 (radar equation, amplitude);
//  - the direct antenna coupling pulse at range 0;
//  - white Gaussian thermal noise.
// Sample k lies at range range_offset_m + k * c / (2 fs), as the imaging frontend reads it.
#pragma once

#include <random>
#include <vector>

#include "drivers/sim/grid_ray_caster.h"
#include "drivers/sim/pulse_table.h"
#include "drivers/sim/sim_environment.h"
#include "drivers/sim/walking_people.h"
#include "imaging/sensor_geometry.h"

namespace uwbsar::sim {

class RadarSimulator {
 public:
  /// Keeps a reference to `environment`, which must outlive the simulator.
  RadarSimulator(const SimEnvironment& environment, const PulseConfig& pulse,
                 const SensorGeometry& sensor, const SimRadarConfig& config);

  /// One scan (sensor.num_samples samples) for the antenna at T_world_sensor (x along
  /// boresight). Noise is drawn from `rng`; nullptr gives a noise-free scan. `movers` (people
  /// walking past, at this instant) each add the echo of their side facing the antenna where
  /// no wall hides it. Not thread-safe: use one simulator per thread.
  std::vector<float> Simulate(const Pose2& T_world_sensor, std::mt19937_64* rng,
                              const std::vector<SimDisc>& movers = {});

  /// Occupied cells the last Simulate() lit (row * cols + col), for tests and metrics.
  const std::vector<int>& lit_cells() const { return lit_cells_; }
  /// Farthest range a scan covers (the last sample's range).
  double max_range_m() const { return max_range_m_; }

 private:
  void AddScatterer(const SimScatterer& s, const Pose2& T_world_sensor, float* scan) const;

  const SimEnvironment& environment_;
  GridRayCaster caster_;
  PulseTable pulse_table_;
  SensorGeometry sensor_;
  SimRadarConfig config_;
  double samples_per_metre_ = 0.0;  ///< two-way: 2 fs / c
  double pattern_k_ = 0.0;          ///< g(theta) = exp(pattern_k * theta^2)
  double max_angle_rad_ = 0.0;
  double max_range_m_ = 0.0;
  double angular_step_rad_ = 0.0;
  std::vector<int> lit_cells_;
};

}  // namespace uwbsar::sim
