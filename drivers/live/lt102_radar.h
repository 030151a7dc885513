// The LT102 behind the radar seam (drivers/live/radar_device.h), model "lt102" of
// live.radar_model: its driver (drivers/live/lt102_driver.h) on a reconnecting serial link
// (drivers/live/device_link.h), and its counts as the generic RadarStats with the LT102's
// own after them (live.json's keys for the LT102).
#pragma once

#include <memory>
#include <string>

#include "drivers/live/device_link.h"
#include "drivers/live/lt102_driver.h"
#include "drivers/live/radar_device.h"

namespace uwbsar::live {

class Lt102Radar : public RadarDevice {
 public:
  explicit Lt102Radar(const RadarDeviceArgs& args);

  void Start() override { link_.Start(); }
  void RequestStop() override { link_.RequestStop(); }
  void Stop() override { link_.Stop(); }
  bool connected() const override { return link_.connected(); }
  bool WaitConfigured(double timeout_s, RadarSetup* setup, std::string* error) override;
  RadarStartupWait startup_wait() const override;
  long long scans() const override { return driver_.scans(); }
  RadarStats stats() const override { return ToRadarStats(driver_.stats()); }

  /// The LT102's counts as RadarStats: the generic counts, then its own (`d` requests and
  /// answers, request-to-answer times, command exchanges, `o` stops).
  static RadarStats ToRadarStats(const Lt102Stats& s);
  static RadarSetup ToRadarSetup(const Lt102Setup& setup);

 private:
  double startup_wait_s_;
  Lt102Driver driver_;
  DeviceLink link_;  // after driver_: its thread stops before the driver goes
};

/// The factory's creator of model "lt102".
std::unique_ptr<RadarDevice> CreateLt102Radar(const RadarDeviceArgs& args);

}  // namespace uwbsar::live
