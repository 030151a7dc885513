// What the live device drivers are given: the core sections (pulse, radars) and live.*, their
// own section. Built from the whole file's struct
// (slam/app_config.h), or any struct with those members, without this folder knowing it.
#pragma once

#include <vector>

#include "core/radar_config.h"
#include "drivers/live/live_config.h"
#include "imaging/pulse_config.h"

namespace uwbsar {

struct LiveSettings {
  PulseConfig pulse;
  std::vector<RadarConfig> radars = DefaultRadars();
  LiveConfig live;

  LiveSettings() = default;
  /// From any configuration holding the core sections and `live` (implicit on purpose).
  template <class WholeConfig>
  LiveSettings(const WholeConfig& config)  // NOLINT(google-explicit-constructor)
      : pulse(config.pulse), radars(config.radars), live(config.live) {}
};

}  // namespace uwbsar
