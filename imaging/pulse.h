// The transmitted pulse: a Gaussian-modulated sinusoid (paper Table I), the
// same model as scipy.signal.gausspulse with the bandwidth measured at -6 dB.
#pragma once

#include <vector>

#include "imaging/pulse_config.h"

namespace uwbsar {

constexpr double kSpeedOfLightMps = 299792458.0;

/// Range covered by one sample of a two-way delay: c / (2 fs) (paper eq. for Delta d).
inline double RangeBinSizeM(const PulseConfig& pulse) {
  return kSpeedOfLightMps / (2.0 * pulse.sampling_frequency_hz);
}

/// Continuous pulse model s(t) = A exp(-a t^2) cos(2 pi fc t).
class GaussianPulse {
 public:
  explicit GaussianPulse(const PulseConfig& config);

  /// s(t), t in seconds relative to the pulse centre.
  double operator()(double t_s) const;
  /// Envelope A exp(-a t^2).
  double Envelope(double t_s) const;
  /// Time after which the envelope is below -60 dB of its peak.
  double HalfSupportS() const { return half_support_s_; }

  /// Samples at fs centred on index CenterIndex(): s((k - center) / fs).
  std::vector<float> Sampled() const;
  int CenterIndex() const;

 private:
  PulseConfig config_;
  double a_ = 0.0;  ///< envelope exponent, 1/s^2
  double half_support_s_ = 0.0;
};

}  // namespace uwbsar
