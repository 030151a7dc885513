// What the live device drivers are given: the core sections (pulse, radars) and live.*, their
// own section; the emulated devices also read simulator.*. Built from the whole file's struct
// (pipeline/app_config.h), or any struct with those members, without this folder knowing it.
#pragma once

#include "drivers/live/live_config.h"
#include "drivers/sim/simulator_config.h"
#include "slam/config.h"

namespace uwbsar {

struct LiveSettings : CoreConfig {
  LiveConfig live;

  LiveSettings() = default;
  /// From any configuration holding the core sections and `live` (implicit on purpose).
  template <class WholeConfig>
  LiveSettings(const WholeConfig& config)  // NOLINT(google-explicit-constructor)
      : CoreConfig(config), live(config.live) {}
};

/// The emulated devices (SimDevicePlayer): live.* and the simulated run's simulator.*.
struct EmulatorSettings : LiveSettings {
  SimulatorConfig simulator;

  EmulatorSettings() = default;
  template <class WholeConfig>
  EmulatorSettings(const WholeConfig& config)  // NOLINT(google-explicit-constructor)
      : LiveSettings(config), simulator(config.simulator) {}
};

}  // namespace uwbsar
