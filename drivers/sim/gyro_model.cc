#include "drivers/sim/gyro_model.h"

#include <algorithm>
#include <cmath>

namespace uwbsar::sim {
namespace {

constexpr double kRadPerDeg = M_PI / 180.0;

}  // namespace

GyroModel::GyroModel(const SimGyroConfig& config, double start_yaw_rad, std::uint64_t seed)
    : config_(config),
      rng_(seed),
      start_yaw_rad_(start_yaw_rad),
      heading_rad_(start_yaw_rad),
      noise_density_rad_per_sqrt_s_(config.rate_noise_density_dps_per_sqrt_hz * kRadPerDeg),
      bias_walk_radps_per_sqrt_s_(config.bias_walk_dps_per_sqrt_s * kRadPerDeg),
      range_radps_(config.range_dps * kRadPerDeg),
      resolution_rad_(config.angle_resolution_deg * kRadPerDeg) {
  // Always draw, so the noise sequence does not depend on whether there is a turn-on bias, nor
  // on whether it is fixed.
  const double sigmas = unit_(rng_);
  bias_radps_ =
      config.turn_on_bias_sigmas.value_or(sigmas) * config.turn_on_bias_std_dps * kRadPerDeg;
}

double GyroModel::Step(double dt_s, double true_dyaw_rad) {
  if (dt_s > 0) {
    // A rate beyond the range is reported as the range: turns that fast are under-reported.
    const double true_rate = true_dyaw_rad / dt_s;
    const double sensed_rate = std::clamp(true_rate, -range_radps_, range_radps_);
    const double sqrt_dt = std::sqrt(dt_s);
    const double noise_rad = unit_(rng_) * noise_density_rad_per_sqrt_s_ * sqrt_dt;
    const double walk = unit_(rng_) * bias_walk_radps_per_sqrt_s_ * sqrt_dt;
    // The bias moves across the step: its mean over the step is the midpoint (exact in the
    // mean; the walk's within-step spread is below the white noise at any realistic rate).
    heading_rad_ += (1.0 + config_.scale_error) * sensed_rate * dt_s +
                    (bias_radps_ + 0.5 * walk) * dt_s + noise_rad;
    bias_radps_ += walk;
  } else {
    heading_rad_ += (1.0 + config_.scale_error) * true_dyaw_rad;
  }
  if (resolution_rad_ <= 0) return heading_rad_;
  // The base counts its angle from its own zero at power-up (the driver subtracts the first
  // reading), so the quantisation is of the heading turned since the start.
  const double turned_rad = heading_rad_ - start_yaw_rad_;
  return start_yaw_rad_ + std::round(turned_rad / resolution_rad_) * resolution_rad_;
}

}  // namespace uwbsar::sim
