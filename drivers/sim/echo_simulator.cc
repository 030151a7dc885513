#include "drivers/sim/echo_simulator.h"

#include <algorithm>
#include <cmath>

namespace uwbsar {

EchoSimulator::EchoSimulator(const PulseConfig& pulse, const SensorGeometry& geometry,
                             const EchoModel& model)
    : pulse_config_(pulse), pulse_(pulse), geometry_(geometry), model_(model) {}

void EchoSimulator::AddEcho(double range_m, double amplitude, std::vector<float>* scan) const {
  const double fs = pulse_config_.sampling_frequency_hz;
  const double delay_s = 2.0 * (range_m - geometry_.range_offset_m) / kSpeedOfLightMps;
  const double centre = delay_s * fs;
  const double half = pulse_.HalfSupportS() * fs;
  const int first = std::max(0, static_cast<int>(std::floor(centre - half)));
  const int last =
      std::min(static_cast<int>(scan->size()) - 1, static_cast<int>(std::ceil(centre + half)));
  for (int k = first; k <= last; ++k) {
    (*scan)[k] += static_cast<float>(amplitude * pulse_(k / fs - delay_s));
  }
}

std::vector<float> EchoSimulator::Simulate(const Pose2& T_world_sensor,
                                           const std::vector<Scatterer>& scatterers,
                                           std::mt19937_64* rng) const {
  std::vector<float> scan(static_cast<std::size_t>(geometry_.num_samples), 0.0f);
  const Pose2 T_sensor_world = T_world_sensor.Inverse();
  // Gaussian two-way pattern in angle: 20 log10 g(theta3) = -3 dB.
  const double theta3 = model_.beam_3db_half_angle_deg * M_PI / 180.0;
  const double k_pattern = std::log(std::pow(10.0, -3.0 / 20.0)) / (theta3 * theta3);
  const double max_angle = model_.max_angle_deg * M_PI / 180.0;
  for (const Scatterer& s : scatterers) {
    const Point2 p = T_sensor_world * s.position_world;
    const double range = std::hypot(p.x_m, p.y_m);
    if (range < 1e-3) continue;
    const double angle = std::atan2(p.y_m, p.x_m);
    if (std::abs(angle) > max_angle) continue;
    double amplitude = s.amplitude;
    if (model_.use_beam_pattern) amplitude *= std::exp(k_pattern * angle * angle);
    if (model_.use_range_loss) amplitude /= range * range;
    AddEcho(range, amplitude, &scan);
  }
  if (model_.coupling_amplitude != 0.0) AddEcho(0.0, model_.coupling_amplitude, &scan);
  if (model_.noise_std > 0.0 && rng != nullptr) {
    std::normal_distribution<double> noise(0.0, model_.noise_std);
    for (float& v : scan) v += static_cast<float>(noise(*rng));
  }
  return scan;
}

}  // namespace uwbsar
