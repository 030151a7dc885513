// Radar echo synthesis for point scatterers: each scatterer in the beam adds the
// transmitted pulse at its two-way delay 2R/c, scaled by its amplitude, the
// two-way beam pattern (-3 dB at the FOV edge) and 1/R^2; plus optional direct
// antenna coupling at range 0 and white thermal noise. The ground truth for the
// imaging tests, and the signal model of the environment simulator.
#pragma once

#include <random>
#include <vector>

#include "core/pose2.h"
#include "imaging/pulse.h"
#include "imaging/pulse_config.h"
#include "imaging/sensor_geometry.h"

namespace uwbsar {

struct Scatterer {
  Point2 position_world;
  double amplitude = 1.0;  ///< sqrt of radar cross-section, arbitrary units
};

struct EchoModel {
  double beam_3db_half_angle_deg = 30.0;  ///< two-way -3 dB angle off boresight
  bool use_beam_pattern = true;
  bool use_range_loss = true;       ///< amplitude ~ 1 / R^2
  double max_angle_deg = 90.0;      ///< scatterers beyond this angle are not seen
  double coupling_amplitude = 0.0;  ///< direct antenna coupling pulse at range 0
  double noise_std = 0.0;           ///< white Gaussian noise per sample
};

class EchoSimulator {
 public:
  EchoSimulator(const PulseConfig& pulse, const SensorGeometry& geometry, const EchoModel& model);

  /// One scan (geometry.num_samples samples) for a sensor at T_world_sensor.
  std::vector<float> Simulate(const Pose2& T_world_sensor, const std::vector<Scatterer>& scatterers,
                              std::mt19937_64* rng) const;
  /// Adds one echo at `range_m` with `amplitude` (no pattern or loss applied).
  void AddEcho(double range_m, double amplitude, std::vector<float>* scan) const;

 private:
  PulseConfig pulse_config_;
  GaussianPulse pulse_;
  SensorGeometry geometry_;
  EchoModel model_;
};

}  // namespace uwbsar
