#include "drivers/sim/radar_simulator.h"

#include <cmath>

#include "imaging/pulse.h"

namespace uwbsar::sim {

RadarSimulator::RadarSimulator(const SimEnvironment& environment, const PulseConfig& pulse,
                               const SensorGeometry& sensor, const SimRadarConfig& config)
    : environment_(environment),
      caster_(environment.grid()),
      pulse_table_(pulse),
      sensor_(sensor),
      config_(config) {
  samples_per_metre_ = 2.0 * pulse.sampling_frequency_hz / kSpeedOfLightMps;
  const double theta3 = config.beam_3db_half_angle_deg * M_PI / 180.0;
  pattern_k_ = std::log(std::pow(10.0, -3.0 / 20.0)) / (theta3 * theta3);
  max_angle_rad_ = config.max_angle_deg * M_PI / 180.0;
  max_range_m_ = sensor.range_offset_m + (sensor.num_samples - 1) * sensor.bin_size_m;
  // Rays close enough that neighbouring rays cannot both miss a cell at the far end.
  angular_step_rad_ = 0.5 * environment.grid().resolution_m / std::max(max_range_m_, 0.1);
}

void RadarSimulator::AddScatterer(const SimScatterer& s, const Pose2& T_world_sensor,
                                  float* scan) const {
  const double dx = s.x_m - T_world_sensor.x_m, dy = s.y_m - T_world_sensor.y_m;
  const double range = std::sqrt(dx * dx + dy * dy);
  if (range < 1e-3 || range > max_range_m_ + 0.2) return;
  const double angle = NormalizeAngle(std::atan2(dy, dx) - T_world_sensor.yaw_rad);
  if (std::abs(angle) > max_angle_rad_) return;
  const double gain = std::exp(pattern_k_ * angle * angle) / (range * range);
  const double delay = (range - sensor_.range_offset_m) * samples_per_metre_;
  pulse_table_.AddEcho(delay, static_cast<float>(gain * s.in_phase),
                       static_cast<float>(gain * s.quadrature), scan, sensor_.num_samples);
}

std::vector<float> RadarSimulator::Simulate(const Pose2& T_world_sensor, std::mt19937_64* rng,
                                            const std::vector<SimDisc>& movers) {
  std::vector<float> scan(static_cast<std::size_t>(sensor_.num_samples), 0.0f);
  const Point2 antenna{T_world_sensor.x_m, T_world_sensor.y_m};
  lit_cells_.clear();
  caster_.LitCells(antenna, T_world_sensor.yaw_rad, max_angle_rad_, max_range_m_,
                   config_.penetration_depth_m, angular_step_rad_, &lit_cells_);
  const std::vector<SimScatterer>& scatterers = environment_.scatterers();
  for (int cell : lit_cells_) {
    for (int i = environment_.CellBegin(cell); i < environment_.CellEnd(cell); ++i) {
      AddScatterer(scatterers[i], T_world_sensor, scan.data());
    }
  }
  // A target standing in (or just behind) the first surface stays visible.
  const double tolerance =
      std::max(config_.penetration_depth_m, 1.5 * environment_.grid().resolution_m);
  for (const SimScatterer& target : environment_.point_targets()) {
    if (caster_.Visible(antenna, {target.x_m, target.y_m}, tolerance)) {
      AddScatterer(target, T_world_sensor, scan.data());
    }
  }
  for (const SimDisc& d : movers) {
    const double dx = antenna.x_m - d.x_m, dy = antenna.y_m - d.y_m;
    const double distance = std::hypot(dx, dy);
    if (distance <= d.radius_m) continue;
    const SimScatterer near{d.x_m + dx / distance * d.radius_m, d.y_m + dy / distance * d.radius_m,
                            d.in_phase, d.quadrature};
    if (caster_.Visible(antenna, {near.x_m, near.y_m}, tolerance)) {
      AddScatterer(near, T_world_sensor, scan.data());
    }
  }
  if (config_.coupling_amplitude != 0.0) {
    pulse_table_.AddEcho(-sensor_.range_offset_m * samples_per_metre_,
                         static_cast<float>(config_.coupling_amplitude), 0.0f, scan.data(),
                         sensor_.num_samples);
  }
  if (config_.noise_std > 0.0 && rng != nullptr) {
    std::normal_distribution<float> noise(0.0f, static_cast<float>(config_.noise_std));
    for (float& v : scan) v += noise(*rng);
  }
  return scan;
}

}  // namespace uwbsar::sim
