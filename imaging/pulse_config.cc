#include "imaging/pulse_config.h"

#include <string>

#include "core/config_require.h"

namespace uwbsar {

using config_validation::Require;

void Validate(const PulseConfig& p, const std::string& src) {
  Require(p.center_frequency_hz > 0, src, "pulse.center_frequency_hz", "must be > 0");
  Require(p.bandwidth_hz > 0, src, "pulse.bandwidth_hz", "must be > 0");
  Require(p.sampling_frequency_hz > 2 * p.center_frequency_hz, src, "pulse.sampling_frequency_hz",
          "must exceed twice the centre frequency");
}

}  // namespace uwbsar
