#include "drivers/sim/pulse_table.h"

#include <algorithm>
#include <cmath>

#include "imaging/pulse.h"

namespace uwbsar::sim {

PulseTable::PulseTable(const PulseConfig& pulse, int fractions) : fractions_(fractions) {
  const GaussianPulse model(pulse);
  const double fs = pulse.sampling_frequency_hz;
  half_ = static_cast<int>(std::ceil(model.HalfSupportS() * fs));
  length_ = 2 * half_ + 2;
  in_phase_.resize(static_cast<std::size_t>(fractions_) * length_);
  quadrature_.resize(in_phase_.size());
  // Row f, entry j: the pulse at sample (k0 - half + j) for an echo centred at k0 + f / F.
  for (int f = 0; f < fractions_; ++f) {
    for (int j = 0; j < length_; ++j) {
      const double t = (j - half_ - static_cast<double>(f) / fractions_) / fs;
      const double phase = 2.0 * M_PI * pulse.center_frequency_hz * t;
      const double envelope = model.Envelope(t);
      in_phase_[static_cast<std::size_t>(f) * length_ + j] =
          static_cast<float>(envelope * std::cos(phase));
      quadrature_[static_cast<std::size_t>(f) * length_ + j] =
          static_cast<float>(envelope * std::sin(phase));
    }
  }
}

void PulseTable::AddEcho(double delay_samples, float in_phase, float quadrature, float* scan,
                         int num_samples) const {
  double whole = std::floor(delay_samples);
  int f = static_cast<int>(std::lround((delay_samples - whole) * fractions_));
  if (f == fractions_) {
    f = 0;
    whole += 1.0;
  }
  if (whole - half_ >= num_samples || whole + half_ + 2 <= 0) return;
  const int first = static_cast<int>(whole) - half_;  // scan index of row entry 0
  const int j0 = std::max(0, -first);
  const int j1 = std::min(length_, num_samples - first);
  const float* p = in_phase_.data() + static_cast<std::size_t>(f) * length_;
  const float* q = quadrature_.data() + static_cast<std::size_t>(f) * length_;
  float* out = scan + (first + j0);
  for (int j = j0; j < j1; ++j, ++out) *out += in_phase * p[j] + quadrature * q[j];
}

}  // namespace uwbsar::sim
