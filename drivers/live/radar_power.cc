#include "drivers/live/radar_power.h"

#include <chrono>
#include <thread>

namespace uwbsar::live {

std::unique_ptr<GpioChip> OpenConfiguredChip(const LiveConfig& config) {
  if (config.gpio_chip.empty()) return nullptr;
  return OpenGpiodChip(config.gpio_chip);
}

RadarPower::RadarPower(std::unique_ptr<GpioChip> chip, const LiveConfig& config, Listener listener)
    : chip_(std::move(chip)), config_(config), listener_(std::move(listener)) {
  if (!chip_) return;
  for (std::size_t i = 0; i < config_.radar_power_lines.size(); ++i) {
    // Off until StartUp: a radar must come up with a clean power-on and reset.
    power_.push_back(chip_->RequestOutput(config_.radar_power_lines[i],
                                          "radar " + std::to_string(i) + " power", false));
  }
  for (std::size_t i = 0; i < config_.radar_reset_lines.size(); ++i) {
    reset_.push_back(chip_->RequestOutput(config_.radar_reset_lines[i],
                                          "radar " + std::to_string(i) + " reset", true));
  }
  if (config_.status_led_line >= 0) {
    led_ = chip_->RequestOutput(config_.status_led_line, "status LED", false);
  }
}

bool RadarPower::can_power_cycle(int radar) const {
  return radar >= 0 && static_cast<std::size_t>(radar) < power_.size();
}

void RadarPower::Set(GpioOutput* line, bool high, const std::string& what) {
  line->Set(high);
  if (listener_) listener_(what + (high ? " high" : " low"));
}

void RadarPower::SleepS(double s) { std::this_thread::sleep_for(std::chrono::duration<double>(s)); }

void RadarPower::ResetPulse(int radar) {
  if (static_cast<std::size_t>(radar) >= reset_.size()) return;
  const std::string what = "radar " + std::to_string(radar) + " reset";
  Set(reset_[static_cast<std::size_t>(radar)].get(), false, what);
  SleepS(config_.reset_pulse_s);
  Set(reset_[static_cast<std::size_t>(radar)].get(), true, what);
}

void RadarPower::StartUp() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (!chip_) return;
  for (std::size_t i = 0; i < power_.size(); ++i) {
    Set(power_[i].get(), true, "radar " + std::to_string(i) + " power");
  }
  if (!power_.empty()) SleepS(config_.power_settle_s);
  for (std::size_t i = 0; i < reset_.size(); ++i) ResetPulse(static_cast<int>(i));
  if (!reset_.empty()) SleepS(config_.power_settle_s);
}

void RadarPower::PowerCycle(int radar) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (!can_power_cycle(radar)) return;
  const std::string what = "radar " + std::to_string(radar) + " power";
  Set(power_[static_cast<std::size_t>(radar)].get(), false, what);
  SleepS(config_.power_off_s);
  Set(power_[static_cast<std::size_t>(radar)].get(), true, what);
  SleepS(config_.power_settle_s);
  ResetPulse(radar);
  SleepS(config_.power_settle_s);
}

void RadarPower::SetStatusLed(bool on) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (led_) Set(led_.get(), on, "status LED");
}

void RadarPower::ShutDown() {
  std::lock_guard<std::mutex> lock(mutex_);
  for (std::size_t i = 0; i < power_.size(); ++i) {
    Set(power_[i].get(), false, "radar " + std::to_string(i) + " power");
  }
  if (led_) Set(led_.get(), false, "status LED");
}

}  // namespace uwbsar::live
