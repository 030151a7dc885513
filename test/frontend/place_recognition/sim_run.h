// Test helper: a run of the environment simulator (drivers/sim) in memory, imaged by
// the real frontend: every imaged scan, the keyframes, and the ground truth.
#pragma once

#include <string>
#include <vector>

#include "drivers/sim/sim_source.h"
#include "frontend/imaging_frontend.h"
#include "slam/app_config.h"
#include "test/frontend/place_recognition/sar_scene.h"
#include "test/shared_data.h"

namespace uwbsar::testing {

struct SimulatedRun {
  std::vector<ImagedScan> scans;  ///< imaged scans (odometry poses)
  std::vector<Keyframe> keyframes;
  std::vector<OdometrySample> ground_truth;
};

inline std::string SeedLabMap() { return ::uwbsar::testing::SeedLabLidarMap(); }

inline SimulatedRun SimulateAndImage(const Config& config, const std::string& map_yaml,
                                     const std::string& route, std::uint64_t seed) {
  const sim::SimScenario scenario = sim::MakeScenario(config, map_yaml, route, seed);
  sim::SimSource source(config, scenario, seed);
  SimulatedRun run;
  ImagingFrontend frontend(config);
  frontend.SetScanObserver([&](const ImagedScan& s) { run.scans.push_back(s); });
  source.Run([&](const Message& m) {
    if (m.kind == Message::Kind::kGroundTruth) run.ground_truth.push_back(m.odometry);
    FeedScanOrOdometry(frontend, m);
    for (Keyframe& k : frontend.TakeKeyframes()) run.keyframes.push_back(std::move(k));
  });
  frontend.Finish();
  for (Keyframe& k : frontend.TakeKeyframes()) run.keyframes.push_back(std::move(k));
  return run;
}

/// Odometry error at a scan: E = T_odom * T_true^-1 (maps true world points to where
/// the odometry-posed images put them).
inline Pose2 OdometryErrorAt(const SimulatedRun& run, const ImagedScan& scan) {
  return scan.T_world_robot * TruePoseAt(run.ground_truth, scan.stamp_ns).Inverse();
}

}  // namespace uwbsar::testing
