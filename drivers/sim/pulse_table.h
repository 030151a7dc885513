// The transmitted pulse pre-sampled at fractional delays, so adding an echo to a
// scan is a short multiply-add over contiguous samples instead of evaluating
// exp and cos per sample. Both the pulse p(t) = env(t) cos(2 pi fc t) and its
// quadrature twin q(t) = env(t) sin(2 pi fc t) are tabulated: an echo with
// phase phi is A cos(phi) p - A sin(phi) q.
#pragma once

#include <vector>

#include "imaging/pulse_config.h"

namespace uwbsar::sim {

class PulseTable {
 public:
  /// `fractions` delays per sample period are tabulated (delay error <= 1 / (2 fractions)
  /// sample; 64 keeps the carrier phase error below 0.03 rad at 7.29 GHz / 23.3 GS/s).
  explicit PulseTable(const PulseConfig& pulse, int fractions = 64);

  /// Adds in_phase * p(t - delay) + quadrature * q(t - delay) to `scan`, sample k at
  /// t = k / fs; `delay_samples` is the echo's delay in samples (may be negative or
  /// past the end: only the overlapping part is added).
  void AddEcho(double delay_samples, float in_phase, float quadrature, float* scan,
               int num_samples) const;

  int half_length() const { return half_; }

 private:
  int fractions_;
  int half_;    ///< samples each side of the centre where the envelope is above -60 dB
  int length_;  ///< 2 * half_ + 2 samples per row
  std::vector<float> in_phase_;    ///< fractions_ rows of length_
  std::vector<float> quadrature_;  ///< same layout
};

}  // namespace uwbsar::sim
