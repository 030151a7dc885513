// Simulated single-axis (yaw) rate gyro, as on the Kobuki base: the true rotation over a
// step is measured with a scale factor error, a constant turn-on bias that then walks
// (random walk of the bias), white rate noise, and a range beyond which the rate saturates;
// the base integrates it into the heading it reports, quantised to its output resolution.
//
// Noise model (continuous time, integrated exactly over each step of length dt):
//   measured rate = (1 + scale_error) * true rate + bias(t) + white noise of density N;
//   bias(t) starts at a draw from N(0, turn_on_bias_std) (or at turn_on_bias_sigmas times
//   turn_on_bias_std, when fixed) and walks with density K.
// Over a step the heading increment then carries the bias times dt and white noise of
// standard deviation N * sqrt(dt), so at standstill the heading error after t seconds has the
// standard deviation N * sqrt(t) around bias * t (plus the walk's K * t^1.5 / sqrt(3)).
#pragma once

#include <cstdint>
#include <random>

#include "drivers/sim/simulator_config.h"

namespace uwbsar::sim {

class GyroModel {
 public:
  /// Starts at heading `start_yaw_rad`; draws the turn-on bias from `seed` unless the
  /// configuration fixes it (turn_on_bias_sigmas).
  GyroModel(const SimGyroConfig& config, double start_yaw_rad, std::uint64_t seed);

  /// Advances by `dt_s` over which the robot truly turned by `true_dyaw_rad`; returns the
  /// heading the base reports after it (quantised, not wrapped).
  double Step(double dt_s, double true_dyaw_rad);

  /// The bias in effect now (turn-on bias plus its walk so far), rad/s.
  double bias_radps() const { return bias_radps_; }
  /// The integrated heading before quantisation, rad (not wrapped).
  double heading_rad() const { return heading_rad_; }

 private:
  SimGyroConfig config_;
  std::mt19937_64 rng_;
  std::normal_distribution<double> unit_{0.0, 1.0};
  double start_yaw_rad_ = 0.0;
  double bias_radps_ = 0.0;
  double heading_rad_ = 0.0;
  double noise_density_rad_per_sqrt_s_ = 0.0;
  double bias_walk_radps_per_sqrt_s_ = 0.0;
  double range_radps_ = 0.0;
  double resolution_rad_ = 0.0;
};

}  // namespace uwbsar::sim
