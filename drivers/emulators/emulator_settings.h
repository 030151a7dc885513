// What the emulated devices (SimDevicePlayer) are given: the live drivers' sections, limits.*
// and the simulated run's simulator.*. Built from the whole file's struct
// (slam/app_config.h), or any struct with those members, without this folder knowing it.
#pragma once

#include "core/limits_config.h"
#include "drivers/live/live_settings.h"
#include "drivers/sim/simulator_config.h"

namespace uwbsar {

/// The emulated devices (SimDevicePlayer): live.* and the simulated run's simulator.*.
struct EmulatorSettings : LiveSettings {
  LimitsConfig limits;
  SimulatorConfig simulator;

  EmulatorSettings() = default;
  template <class WholeConfig>
  EmulatorSettings(const WholeConfig& config)  // NOLINT(google-explicit-constructor)
      : LiveSettings(config), limits(config.limits), simulator(config.simulator) {}
};

}  // namespace uwbsar
