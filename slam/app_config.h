// What the SLAM library reads of the configuration file: the SLAM system's sections
// (slam/config/system_config.h) and the sections of the drivers and the session it runs,
// each defined beside the code that owns it (drivers/sim, drivers/live, drivers/dds,
// slam/session). The whole file adds the evaluation's sections above it (app/app_config.h,
// whose loader is app/app_config_io.h). Only slam/, app/ and tools/ hold it: every module
// below is given its own sections.
#pragma once

#include "drivers/dds/dds_config.h"
#include "drivers/live/live_config.h"
#include "drivers/sim/simulator_config.h"
#include "slam/config/system_config.h"
#include "slam/session/session_config.h"

namespace uwbsar {

struct Config : SystemConfig {
  SimulatorConfig simulator;
  LiveConfig live;
  DdsConfig dds;
  SessionConfig session;

  /// The core sections (SystemConfig::Visit), then these: each section is listed once, by the
  /// struct that holds it.
  template <class V>
  void Visit(V& v) {
    SystemConfig::Visit(v);
    v("simulator", simulator);
    v("live", live);
    v("dds", dds);
    v("session", session);
  }
};

}  // namespace uwbsar
