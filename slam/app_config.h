// The whole configuration file: the SLAM system's sections (slam/config/system_config.h) and
// the other sections, each defined beside the code that owns it (drivers/sim, drivers/live,
// drivers/dds, eval/compare, slam/session). config/default.yaml mirrors it field by field; the
// loader is slam/app_config_io.h. Only slam/ and tools/ hold the whole file: every module
// below is given its own sections.
#pragma once

#include "drivers/dds/dds_config.h"
#include "drivers/live/live_config.h"
#include "drivers/sim/simulator_config.h"
#include "eval/compare/compare_config.h"
#include "slam/config/system_config.h"
#include "slam/session/session_config.h"

namespace uwbsar {

struct Config : SystemConfig {
  SimulatorConfig simulator;
  CompareConfig compare;
  LiveConfig live;
  DdsConfig dds;
  SessionConfig session;

  /// Every section in the file's order (config/default.yaml); SystemConfig::Visit lists the
  /// core ones in the same relative order.
  template <class V>
  void Visit(V& v) {
    v("slam", slam);
    v("pulse", pulse);
    v("radars", radars);
    v("imaging", imaging);
    v("gating", gating);
    v("keyframe", keyframe);
    v("enhance", enhance);
    v("backend", backend);
    v("simulator", simulator);
    v("place_recognition", place_recognition);
    v("compare", compare);
    v("live", live);
    v("dds", dds);
    v("limits", limits);
    v("session", session);
  }
};

}  // namespace uwbsar
