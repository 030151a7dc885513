// The whole configuration file: the core sections (slam/config.h) and the sections owned by
// higher folders, each defined beside its code (drivers/sim, drivers/live, drivers/dds,
// backend/compare, session). config/default.yaml mirrors it field by field; the loader is
// pipeline/app_config_io.h. Only pipeline/ and tools/ hold the whole file: every module
// below is given its own sections.
#pragma once

#include "backend/compare/compare_config.h"
#include "drivers/dds/dds_config.h"
#include "drivers/live/live_config.h"
#include "drivers/sim/simulator_config.h"
#include "session/session_config.h"
#include "slam/config.h"

namespace uwbsar {

struct Config : CoreConfig {
  SimulatorConfig simulator;
  CompareConfig compare;
  LiveConfig live;
  DdsConfig dds;
  SessionConfig session;

  /// Every section in the file's order (config/default.yaml); CoreConfig::Visit lists the
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
