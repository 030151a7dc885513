// Radar power and reset through GPIO, plus the status LED, as the live config wires
// them (live.gpio_chip, radar_power_lines, radar_reset_lines, status_led_line).
// Start-up: every radar's power enable high, settle, reset pulse (active low), settle.
// A power cycle (after repeated link failures): power low for power_off_s, then the
// start-up sequence for that radar. With no chip configured every call is a no-op
// (documented "no GPIO" setting). Each line change is passed to the event listener
// so the recording holds the GPIO history. Thread-safe.
#pragma once

#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "drivers/live/gpio.h"
#include "drivers/live/live_config.h"

namespace uwbsar::live {

class RadarPower {
 public:
  using Listener = std::function<void(const std::string& event)>;

  /// Requests every configured line of `chip` (may be null when live.gpio_chip is empty).
  /// Throws GpioError naming the chip, line and role when a line cannot be requested.
  RadarPower(std::unique_ptr<GpioChip> chip, const LiveConfig& config, Listener listener = {});

  bool has_gpio() const { return chip_ != nullptr; }
  bool can_power_cycle(int radar) const;
  /// Powers every radar on and resets it.
  void StartUp();
  void PowerCycle(int radar);
  void SetStatusLed(bool on);
  /// Powers the radars off (end of run); the LED goes off.
  void ShutDown();

 private:
  void Set(GpioOutput* line, bool high, const std::string& what);
  void SleepS(double s);
  void ResetPulse(int radar);

  std::unique_ptr<GpioChip> chip_;
  LiveConfig config_;
  Listener listener_;
  std::vector<std::unique_ptr<GpioOutput>> power_, reset_;
  std::unique_ptr<GpioOutput> led_;
  std::mutex mutex_;
};

/// The chip of a config: null for "no GPIO" (empty live.gpio_chip), else libgpiod.
std::unique_ptr<GpioChip> OpenConfiguredChip(const LiveConfig& config);

}  // namespace uwbsar::live
