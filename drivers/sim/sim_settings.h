// What the simulator is given: the core sections it images with (pulse, radars, limits) and
// simulator.*, its own section. Built from the whole file's struct (slam/app_config.h),
// or any struct with those members, without this folder knowing it.
#pragma once

#include <vector>

#include "core/limits_config.h"
#include "core/radar_config.h"
#include "drivers/sim/simulator_config.h"
#include "imaging/pulse_config.h"

namespace uwbsar {

struct SimSettings {
  PulseConfig pulse;
  std::vector<RadarConfig> radars = DefaultRadars();
  LimitsConfig limits;
  SimulatorConfig simulator;

  SimSettings() = default;
  /// From any configuration holding the core sections and `simulator` (implicit on purpose:
  /// callers hand their whole configuration, the simulator keeps its part).
  template <class WholeConfig>
  SimSettings(const WholeConfig& config)  // NOLINT(google-explicit-constructor)
      : pulse(config.pulse),
        radars(config.radars),
        limits(config.limits),
        simulator(config.simulator) {}
};

}  // namespace uwbsar
