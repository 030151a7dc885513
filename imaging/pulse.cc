#include "imaging/pulse.h"

#include <cmath>

namespace uwbsar {

GaussianPulse::GaussianPulse(const PulseConfig& config) : config_(config) {
  // scipy.signal.gausspulse: with the fractional bandwidth bw = B / fc measured at
  // bwr = -6 dB, a = -(pi fc bw)^2 / (4 ln(10^(bwr/20))).
  const double ref = std::pow(10.0, -6.0 / 20.0);
  const double pi_b = M_PI * config.bandwidth_hz;
  a_ = -(pi_b * pi_b) / (4.0 * std::log(ref));
  const double tref = std::pow(10.0, -60.0 / 20.0);
  half_support_s_ = std::sqrt(-std::log(tref) / a_);
}

double GaussianPulse::Envelope(double t_s) const {
  return config_.amplitude_v * std::exp(-a_ * t_s * t_s);
}

double GaussianPulse::operator()(double t_s) const {
  return Envelope(t_s) * std::cos(2.0 * M_PI * config_.center_frequency_hz * t_s);
}

int GaussianPulse::CenterIndex() const {
  return static_cast<int>(std::ceil(half_support_s_ * config_.sampling_frequency_hz));
}

std::vector<float> GaussianPulse::Sampled() const {
  const int center = CenterIndex();
  std::vector<float> samples(static_cast<std::size_t>(2 * center + 1));
  for (int k = 0; k < static_cast<int>(samples.size()); ++k) {
    samples[k] = static_cast<float>((*this)((k - center) / config_.sampling_frequency_hz));
  }
  return samples;
}

}  // namespace uwbsar
