// Settings of pulse.*, declared beside the code that owns them (imaging/pulse.h); the application
// configuration (slam/config/system_config.h, slam/app_config.h) assembles the sections, and
// core/config_io.h reads and writes any struct with a Visit(). config/default.yaml
// documents every field; a test keeps the two in sync.
#pragma once

#include <string>

namespace uwbsar {

/// Transmitted pulse and receiver sampling (paper Table I).
struct PulseConfig {
  double center_frequency_hz = 7.29e9;  ///< fc
  double bandwidth_hz = 1.4e9;          ///< -6 dB bandwidth (reference code; paper table: 2 GHz)
  double sampling_frequency_hz = 23.328e9;  ///< fs; one range bin = c / (2 fs)
  double amplitude_v = 0.6;                 ///< pulse amplitude (reference code; paper: 1.0 V)

  template <class V>
  void Visit(V& v) {
    v("center_frequency_hz", center_frequency_hz);
    v("bandwidth_hz", bandwidth_hz);
    v("sampling_frequency_hz", sampling_frequency_hz);
    v("amplitude_v", amplitude_v);
  }
};
/// Semantic checks of pulse.*; throws ConfigError naming the dotted key.
void Validate(const PulseConfig& config, const std::string& source_name);

}  // namespace uwbsar
