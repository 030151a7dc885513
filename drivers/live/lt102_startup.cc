#include "drivers/live/lt102_startup.h"

#include <cmath>
#include <cstdio>

namespace uwbsar::live {
namespace {

constexpr double kSpeedOfLight = 299792458.0;
constexpr double kCarrierTolerance = 0.01;  ///< the issue's 1 % carrier check

Lt102Request Set(std::uint8_t code, double value) { return {code, false, value}; }
Lt102Request Query(std::uint8_t code) { return {code, true, 0.0}; }
Lt102Request Plain(std::uint8_t code) { return {code, false, 0.0}; }

}  // namespace

std::string Lt102Setup::Describe() const {
  char asked[48] = "";
  if (frame_rate_requested_fps != frame_rate_fps) {
    std::snprintf(asked, sizeof(asked), " (%d asked)", frame_rate_requested_fps);
  }
  char text[480];
  std::snprintf(text, sizeof(text),
                "LT102 %s; CRC %s; output %d%s; range %.4f-%.4f m (%d samples), first-sample "
                "offset %.4f m; frame rate %d fps%s; carrier %d MHz, bandwidth %d MHz, TX power "
                "%d, ADC frequency %d",
                version.ToString().c_str(), crc ? "on" : "off", output,
                output == 0 ? " (last reading)" : "", range_min_m, range_max_m, samples_per_scan,
                offset_m, frame_rate_fps, asked, carrier_mhz, bandwidth_mhz, tx_power,
                adc_frequency);
  return text;
}

int Lt102SampleCount(double range_min_m, double range_max_m, double bin_m) {
  return static_cast<int>(std::llround((range_max_m - range_min_m) / bin_m)) + 1;
}

std::vector<Lt102Request> Lt102StartupRequests(const Lt102Config& c) {
  return {
      Plain(lt102::kVersion),
      Plain(lt102::kStop),
      Set(lt102::kProcessing, 0),  // raw
      Set(lt102::kOutput, 0),      // last reading: not slow-time filtered, not evaluated
      Set(lt102::kChannel, c.channel),
      Set(lt102::kFormat, c.sample_format),
      Set(lt102::kRangeMin, c.range_min_m),
      Set(lt102::kRangeMax, c.range_max_m),
      Query(lt102::kOffset),
      Set(lt102::kFrameRate, c.frame_rate_fps),
      Query(lt102::kCarrier),
      Query(lt102::kBandwidth),
      Query(lt102::kTxPower),
      Query(lt102::kAdcFrequency),
      Plain(lt102::kStart),
  };
}

namespace {

/// A setting the radar must echo exactly, compared as the request was encoded (integers
/// wrap like the wire does).
void CheckExactEcho(const Lt102Command& command, const Lt102Request& request, double value,
                    const std::string& name) {
  std::vector<std::uint8_t> sent, got;
  AppendLt102Value(command.request, request.value, &sent);
  AppendLt102Value(command.request, value, &got);
  if (sent != got) {
    throw Lt102ConfigError(name + ": configuration error: " + Lt102CommandLabel(request.code) +
                           " sent " + FormatLt102Value(command.request, request.value) +
                           ", the radar echoed " + FormatLt102Value(command.answer, value));
  }
}

/// Records the answer to `code` in `setup`.
void StoreAnswer(std::uint8_t code, double value, Lt102Setup* setup) {
  switch (code) {
    case lt102::kRangeMin:
      setup->range_min_m = value;
      break;
    case lt102::kRangeMax:
      setup->range_max_m = value;
      break;
    case lt102::kOffset:
      setup->offset_m = value;
      break;
    case lt102::kOutput:
      setup->output = static_cast<int>(value);
      break;
    case lt102::kFrameRate:
      setup->frame_rate_fps = static_cast<int>(value);
      break;
    case lt102::kCarrier:
      setup->carrier_mhz = static_cast<int>(value);
      break;
    case lt102::kBandwidth:
      setup->bandwidth_mhz = static_cast<int>(value);
      break;
    case lt102::kTxPower:
      setup->tx_power = static_cast<int>(value);
      break;
    case lt102::kAdcFrequency:
      setup->adc_frequency = static_cast<int>(value);
      break;
    default:
      break;
  }
}

/// The echoed range sets the samples per scan; a range giving fewer than two is refused.
void SetSamplesPerScan(const LiveSettings& config, const std::string& name, Lt102Setup* setup) {
  const double bin_m = kSpeedOfLight / (2.0 * config.pulse.sampling_frequency_hz);
  setup->samples_per_scan = Lt102SampleCount(setup->range_min_m, setup->range_max_m, bin_m);
  if (!std::isfinite(setup->range_min_m) || !std::isfinite(setup->range_max_m) ||
      setup->samples_per_scan < 2) {
    throw Lt102ConfigError(name + ": configuration error: the radar echoed range " +
                           FormatLt102Value(Lt102Value::kF32, setup->range_min_m) + "-" +
                           FormatLt102Value(Lt102Value::kF32, setup->range_max_m) + " m for " +
                           FormatLt102Value(Lt102Value::kF32, config.live.lt102.range_min_m) + "-" +
                           FormatLt102Value(Lt102Value::kF32, config.live.lt102.range_max_m) +
                           " m asked (live.lt102.range_min_m / range_max_m)");
  }
}

/// The radar's carrier must be within kCarrierTolerance of pulse.center_frequency_hz.
void CheckCarrier(double carrier_mhz, const Lt102Setup& setup, const LiveSettings& config,
                  const std::string& name) {
  const double fc_hz = config.pulse.center_frequency_hz;
  const double off = std::abs(carrier_mhz * 1e6 - fc_hz) / fc_hz;
  if (off > kCarrierTolerance) {
    char text[200];
    std::snprintf(text, sizeof(text),
                  "the radar's carrier is %d MHz, pulse.center_frequency_hz is %.0f MHz "
                  "(%.1f %% apart, more than 1 %%): set pulse.center_frequency_hz to %de6 to "
                  "image with this radar",
                  setup.carrier_mhz, fc_hz / 1e6, 100.0 * off, setup.carrier_mhz);
    throw Lt102ConfigError(name + ": configuration error: " + text);
  }
}

/// The actual frame rate paces the polling: any rate of at least 1 frame/s is taken (and
/// logged when it differs from the one asked); below that nothing can be polled.
void CheckFrameRate(const Lt102Setup& setup, const std::string& name) {
  if (setup.frame_rate_fps >= 1) return;
  throw Lt102ConfigError(name + ": configuration error: the radar answered frame rate " +
                         std::to_string(setup.frame_rate_fps) + " fps to " +
                         std::to_string(setup.frame_rate_requested_fps) +
                         " asked: set live.lt102.frame_rate_fps to a rate it supports");
}

}  // namespace

Lt102Setup RunLt102Startup(SerialPort& port, Lt102Exchange& exchange, const LiveSettings& config,
                           const std::string& name) {
  Lt102Setup setup;
  setup.frame_rate_requested_fps = config.live.lt102.frame_rate_fps;
  for (const Lt102Request& request : Lt102StartupRequests(config.live.lt102)) {
    const std::vector<std::uint8_t> answer = exchange.Ask(port, request);
    const Lt102Command& command = *FindLt102Command(request.code);
    if (command.answer == Lt102Value::kVersion) {
      setup.version = ReadLt102Version(answer.data());
      setup.crc = exchange.crc_enabled();
      continue;
    }
    if (command.answer == Lt102Value::kNone) continue;
    const double value = ReadLt102Value(command.answer, answer.data());
    if (command.echo == Lt102Echo::kExact && !request.query) {
      CheckExactEcho(command, request, value, name);
    }
    StoreAnswer(request.code, value, &setup);
    if (request.code == lt102::kRangeMax) SetSamplesPerScan(config, name, &setup);
    if (request.code == lt102::kCarrier) CheckCarrier(value, setup, config, name);
    if (request.code == lt102::kFrameRate) CheckFrameRate(setup, name);
  }
  return setup;
}

}  // namespace uwbsar::live
