// The LT102 start-up sequence (commands in lt102_commands.h), in order, each step
// one request and its checked answer (lt102_exchange.h): firmware version (logged; its
// length tells whether frames carry a CRC), stop (`o`), raw output (`e` 0), data channel
// (`$`), sample format (0x0A), range minimum / maximum (`x`, `X`: the echoed actual values
// set the range of sample 0 and the sample count), frame rate (`f`), then queries only for
// carrier frequency, pulse bandwidth, PRF divider, TX power and ADC frequency, then start
// (`s`, answered `r`). An echo that differs from the request, or a carrier more than 1 %
// from pulse.center_frequency_hz, is an Lt102ConfigError.
#pragma once

#include <string>
#include <vector>

#include "drivers/live/live_settings.h"
#include "drivers/live/lt102_exchange.h"

namespace uwbsar::live {

/// What the radar reported during start-up.
struct Lt102Setup {
  Lt102Version version;
  bool crc = false;
  double range_min_m = 0.0;  ///< echoed: range of sample 0
  double range_max_m = 0.0;  ///< echoed: range of the last sample
  int samples_per_scan = 0;  ///< from the echoed range and the bin size c / (2 fs)
  int frame_rate_fps = 0;
  int carrier_mhz = 0, bandwidth_mhz = 0, prf_divider = 0, tx_power = 0, adc_frequency = 0;
  /// One line for the log and the recording's events.
  std::string Describe() const;
};

/// The requests of the start-up sequence for `config`, in order.
std::vector<Lt102Request> Lt102StartupRequests(const Lt102Config& config);

/// Runs the sequence on `port`. Throws Lt102ConfigError (a setting refused or contradicting
/// the configuration) or SerialError (no or wrong answers after a retry, port gone).
Lt102Setup RunLt102Startup(SerialPort& port, Lt102Exchange& exchange, const LiveSettings& config,
                           const std::string& name);

/// Samples of a scan from `range_min_m` to `range_max_m` at `bin_m` spacing.
int Lt102SampleCount(double range_min_m, double range_max_m, double bin_m);

}  // namespace uwbsar::live
