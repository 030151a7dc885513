// Shared set-up of the session tests on short simulated seed_lab runs.
#pragma once

#include <cstdlib>
#include <functional>
#include <string>
#include <vector>

#include "core/errors.h"
#include "core/types.h"
#include "slam/app_config.h"

namespace uwbsar::testing {

/// Run A: a 4 m depart-and-return.
inline Config ShortSessionConfig() {
  Config c;
  c.simulator.route.depart_distance_m = 4.0;
  return c;
}

/// Run B of `a`: starts 2 m further along and 20 deg turned, 2.5 m out and back.
inline Config TurnedRevisitConfig(const Config& a) {
  Config b = a;
  b.simulator.route.start_x_m += 2.0;
  b.simulator.route.start_yaw_deg += 20.0;
  b.simulator.route.depart_distance_m = 2.5;
  return b;
}

/// The ground-truth sample nearest `t` (`gt` not empty).
inline const OdometrySample& NearestGroundTruth(const std::vector<OdometrySample>& gt,
                                                TimestampNs t) {
  const OdometrySample* best = &gt.front();
  for (const OdometrySample& g : gt) {
    if (std::llabs(g.stamp_ns - t) < std::llabs(best->stamp_ns - t)) best = &g;
  }
  return *best;
}

/// The message of the InputError `f` throws; "" when it throws none.
inline std::string ErrorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace uwbsar::testing
