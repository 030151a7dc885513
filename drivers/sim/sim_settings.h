// What the simulator is given: the core sections it images with (pulse, radars, limits) and
// simulator.*, its own section. Built from the whole file's struct (pipeline/app_config.h),
// or any struct with those members, without this folder knowing it.
#pragma once

#include "drivers/sim/simulator_config.h"
#include "slam/config.h"

namespace uwbsar {

struct SimSettings : CoreConfig {
  SimulatorConfig simulator;

  SimSettings() = default;
  /// From any configuration holding the core sections and `simulator` (implicit on purpose:
  /// callers hand their whole configuration, the simulator keeps its part).
  template <class WholeConfig>
  SimSettings(const WholeConfig& config)  // NOLINT(google-explicit-constructor)
      : CoreConfig(config), simulator(config.simulator) {}
};

}  // namespace uwbsar
