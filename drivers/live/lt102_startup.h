// The LT102 start-up sequence (commands in lt102_commands.h), in order, each step
// one request and its checked answer (lt102_exchange.h): firmware version (logged; its
// length tells whether frames carry a CRC), stop (`o`), raw processing (`e` 0), output
// "last reading" (`b` 0, so a module left filtering by another program feeds raw frames),
// data channel (`$`), sample format (0x0A), range minimum / maximum (`x`, `X`: the echoed
// actual values set the range of sample 0 and the sample count), first-sample offset (`0`,
// queried and logged), frame rate (`f`: the answer is the rate the radar actually runs at,
// which paces the polling), then queries for carrier frequency, pulse bandwidth, TX power and
// ADC frequency, then start (`s`, answered `r`). Only values the vendor table defines are
// sent: a query only where the table gives a query value (the PRF divider `v` has none and
// is left alone). An exact-echo setting answered differently, an actual frame rate below 1,
// or a carrier more than 1 % from pulse.center_frequency_hz (what imaging uses) is an
// Lt102ConfigError naming the key to set.
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
  double range_min_m = 0.0;          ///< echoed: range of sample 0
  double range_max_m = 0.0;          ///< echoed: range of the last sample
  int samples_per_scan = 0;          ///< from the echoed range and the bin size c / (2 fs)
  double offset_m = 0.0;             ///< queried first-sample offset (`0`), logged
  int output = 0;                    ///< echoed output mode (`b`): 0 = last reading
  int frame_rate_fps = 0;            ///< the radar's actual frame rate (`f` answer)
  int frame_rate_requested_fps = 0;  ///< live.lt102.frame_rate_fps as sent
  int carrier_mhz = 0, bandwidth_mhz = 0, tx_power = 0, adc_frequency = 0;
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
