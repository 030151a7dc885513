#include "slam/localization/localize_job.h"

#include <chrono>
#include <cmath>
#include <cstdio>

#include "core/errors.h"
#include "core/log.h"
#include "drivers/rosbag/bag_reader.h"
#include "drivers/rosbag/bag_source.h"
#include "drivers/rosbag/robot_bag.h"
#include "drivers/sim/sim_source.h"
#include "frontend/imaging_frontend.h"
#include "imaging/image_io.h"
#include "slam/app_config.h"
#include "slam/localization/localize_pipeline.h"
#include "slam/map_job.h"
#include "slam/progress.h"

namespace uwbsar::slam {
namespace {

using Clock = std::chrono::steady_clock;

}  // namespace

std::vector<std::pair<TimestampNs, Pose2>> LocalizeRun::Trajectory(bool tracking_only) const {
  std::vector<std::pair<TimestampNs, Pose2>> out;
  if (first_fix < 0) return out;
  std::size_t k = static_cast<std::size_t>(first_fix);
  for (const OdometryEntry& e : odometry) {
    while (k + 1 < keyframes.size() && keyframes[k + 1].stamp_ns <= e.stamp_ns) ++k;
    const LocalizedKeyframe& kf = keyframes[k];
    if (tracking_only && kf.status == LocalizeStatus::kLost) continue;
    out.push_back({e.stamp_ns, kf.T_map_anchor * kf.T_odom_anchor.Inverse() * e.T_world_robot});
  }
  return out;
}

LocalizeRun LocalizeSource(const SessionData& map, const Config& config,
                           const std::string& description, MessageSource& source,
                           const std::function<void(TimestampNs)>& on_message) {
  LocalizePipeline pipeline(map, config, description);
  std::vector<OdometrySample> ground_truth;
  // The feeding thread's time (imaging, hand-over, waiting for the keyframe thread when
  // it falls behind and at the end), not the source's.
  double busy_s = 0.0;
  source.Run([&](const Message& m) {
    if (on_message) on_message(m.stamp_ns);
    if (m.kind == Message::Kind::kGroundTruth) ground_truth.push_back(m.odometry);
    if (m.kind != Message::Kind::kRadarScan && m.kind != Message::Kind::kOdometry) return;
    const auto t0 = Clock::now();
    FeedScanOrOdometry(pipeline, m);
    busy_s += std::chrono::duration<double>(Clock::now() - t0).count();
  });
  const auto t0 = Clock::now();
  pipeline.Finish();
  busy_s += std::chrono::duration<double>(Clock::now() - t0).count();
  LocalizeRun run = pipeline.Result();
  run.ground_truth = std::move(ground_truth);
  run.frontend_stats = pipeline.frontend_stats();
  run.backend = config.backend;
  run.processing_s = busy_s;
  if (run.odometry.size() >= 2) {
    run.log_duration_s = NsToSeconds(run.odometry.back().stamp_ns - run.odometry.front().stamp_ns);
  }
  if (run.keyframes.empty()) {
    throw InputError(description + ": no keyframe could be imaged (odometry and radar topics?)");
  }
  char line[200];
  std::snprintf(line, sizeof(line),
                "stage localisation: %.3f s, %zu keyframes, first fix %s after %.2f m", busy_s,
                run.keyframes.size(), run.first_fix >= 0 ? "found" : "not found",
                run.first_fix_path_m);
  Log(LogLevel::kDebug, line);
  return run;
}

LocalizeRun LocalizeBag(const SessionData& map, const Config& config, const std::string& bag,
                        bool progress) {
  rosbag::BagReader reader(bag);
  rosbag::BagSource source(reader, rosbag::RobotBagOptionsFromConfig(config));
  const TimestampNs start = reader.Info().start_ns, end = reader.Info().end_ns;
  char what[64];
  std::snprintf(what, sizeof(what), "of %.0f s of log",
                (static_cast<double>(end) - static_cast<double>(start)) * 1e-9);
  ProgressBar bar(progress, what);
  return LocalizeSource(map, config, bag, source,
                        [&](TimestampNs t) { bar.UpdateStamp(t, start, end); });
}

LocalizeRun LocalizeSimulation(const SessionData& map, const Config& config,
                               const std::string& map_yaml, const std::string& route,
                               std::uint64_t scene_seed, std::uint64_t seed,
                               const Pose2& T_odom_world) {
  const sim::SimScenario scenario = sim::MakeScenario(config, map_yaml, route, scene_seed);
  sim::SimSource source(config, scenario, seed, T_odom_world);
  const std::string description =
      "simulated " + route + " in " + map_yaml + " (seed " + std::to_string(seed) + ")";
  return LocalizeSource(map, config, description, source);
}

}  // namespace uwbsar::slam
