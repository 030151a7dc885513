#include "slam/map_job.h"

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "core/errors.h"
#include "core/log.h"
#include "drivers/logs/tum_reader.h"
#include "drivers/rosbag/bag_reader.h"
#include "drivers/rosbag/bag_source.h"
#include "drivers/rosbag/robot_bag.h"
#include "drivers/sim/sim_source.h"
#include "slam/app_config.h"
#include "slam/progress.h"

namespace uwbsar::slam {
namespace {

/// The per-stage log of a finished run (`-v`): what each stage of the pipeline did and the
/// time it took.
void LogStages(const MapRun& run) {
  if (GetLogLevel() > LogLevel::kDebug) return;
  const SlamSystem& slam = *run.slam;
  const FrontendStats& f = slam.frontend_stats();
  const StageTimes& t = slam.times();
  int accepted = 0;
  for (const LoopRecord& l : slam.loops()) accepted += l.accepted();
  char line[256];
  std::snprintf(line, sizeof(line), "input: %lld messages (%lld radar, %lld odometry) of %s",
                run.messages, run.radar_messages, run.odometry_messages, run.input.c_str());
  Log(LogLevel::kDebug, line);
  std::snprintf(line, sizeof(line),
                "stage imaging: %.3f s, %lld scans imaged of %lld (%lld gated, %lld rejected)",
                t.imaging_s, f.scans_imaged, f.scans_received, f.scans_gated, f.scans_rejected());
  Log(LogLevel::kDebug, line);
  std::snprintf(line, sizeof(line), "stage features: %.3f s, %zu keyframes", t.features_s,
                slam.keyframes().size());
  Log(LogLevel::kDebug, line);
  std::snprintf(line, sizeof(line), "stage matching: %.3f s, %zu loop candidates, %d accepted",
                t.matching_s, slam.loops().size(), accepted);
  Log(LogLevel::kDebug, line);
  std::snprintf(line, sizeof(line), "stage optimisation: %.3f s, %s", t.optimization_s,
                slam.last_optimization().termination.c_str());
  Log(LogLevel::kDebug, line);
}

/// Finishes a streamed run: the last keyframes, processing time as SLAM's own, checks.
void FinishStreamed(MapRun* run) {
  run->slam->Finish();
  LogStages(*run);
  // The source (e.g. the simulator) is not part of the mapping: count SLAM's own time.
  const StageTimes& t = run->slam->times();
  run->processing_s = t.imaging_s + t.features_s + t.matching_s + t.optimization_s;
  CheckMappable(*run);
}

}  // namespace

double MapRun::log_duration_s() const {
  double first = 0.0, last = 0.0;
  bool any = false;
  if (slam) {
    for (const KeyframeRecord& k : slam->keyframes()) {
      for (const ImagedScan& s : k.keyframe.scans) {
        const double t = static_cast<double>(s.stamp_ns);
        first = any ? std::min(first, t) : t;
        last = any ? std::max(last, t) : t;
        any = true;
      }
    }
  }
  if (!any) {
    first = static_cast<double>(first_stamp_ns);
    last = static_cast<double>(last_stamp_ns);
  }
  return std::max(0.0, (last - first) * 1e-9);
}

void CheckMappable(const MapRun& run) {
  const FrontendStats& s = run.slam->frontend_stats();
  if (run.odometry_messages == 0) {
    throw InputError(run.input + ": no odometry messages on '" +
                     run.slam->config().slam.odometry_topic + "' (slam.odometry_topic)");
  }
  if (run.radar_messages == 0) {
    throw InputError(run.input + ": no radar scans on the topics of radars[].topic");
  }
  // Scans whose samples passed validation: all zero means radars powered but silent, whose
  // map would be empty (it ended in an OpenCV assertion writing map_float.tif).
  if (s.all_valid_scans_zero()) {
    throw InputError(run.input + ": nothing imaged: every radar scan is zero (" +
                     std::to_string(s.scans_valid()) + " scans; radars powered but silent?)");
  }
  if (s.scans_imaged == 0) {
    throw InputError(run.input + ": no radar scan could be imaged (" +
                     std::to_string(s.scans_rejected_no_odometry + s.scans_rejected_stale) +
                     " without odometry covering their time, " +
                     std::to_string(s.scans_rejected_length + s.scans_rejected_nonfinite +
                                    s.scans_rejected_empty) +
                     " malformed, " + std::to_string(s.scans_gated) + " while not moving)" +
                     s.BadSamplesNote());
  }
  if (run.slam->keyframes().empty()) {
    throw InputError(run.input + ": the run is too short for one keyframe tile");
  }
}

MapRun MapBag(const Config& config, const std::string& bag_path, bool progress,
              const rosbag::BagReadOptions& read_options) {
  MapRun run;
  run.input = bag_path;
  const auto t0 = std::chrono::steady_clock::now();
  // One reader for the progress range and the messages: a file-compressed bag is
  // decompressed once.
  rosbag::BagReader reader(bag_path, read_options);
  const TimestampNs start = reader.Info().start_ns, end = reader.Info().end_ns;
  run.slam = std::make_unique<SlamSystem>(config);
  const rosbag::RobotBagOptions options = rosbag::RobotBagOptionsFromConfig(config);
  {
    char what[64];
    std::snprintf(what, sizeof(what), "of %.0f s of log",
                  (static_cast<double>(end) - static_cast<double>(start)) * 1e-9);
    ProgressBar bar(progress, what);
    rosbag::BagSource source(reader, options);
    source.Run([&](const Message& m) {
      bar.UpdateStamp(m.stamp_ns, start, end);
      Feed(&run, m);
    });
  }
  run.slam->Finish();
  run.processing_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  LogStages(run);
  CheckMappable(run);
  return run;
}

MapRun MapSource(const Config& config, const std::string& description, MessageSource& source,
                 const std::function<void(MapRun*)>& on_message) {
  MapRun run;
  run.input = description;
  run.slam = std::make_unique<SlamSystem>(config);
  source.Run([&](const Message& m) {
    Feed(&run, m);
    if (on_message) on_message(&run);
  });
  FinishStreamed(&run);
  return run;
}

MapRun MapSimulation(const Config& config, const std::string& map_yaml, const std::string& route,
                     std::uint64_t seed, const std::function<void(MapRun*)>& on_message,
                     bool progress) {
  const sim::SimScenario scenario = sim::MakeScenario(config, map_yaml, route, seed);
  sim::SimSource source(config, scenario, seed);
  const std::string description =
      "simulated " + route + " in " + map_yaml + " (seed " + std::to_string(seed) + ")";
  const double duration_s = scenario.trajectory.duration_s();
  char what[64];
  std::snprintf(what, sizeof(what), "of %.0f s of simulated run", duration_s);
  ProgressBar bar(progress, what);
  return MapSource(config, description, source, [&](MapRun* run) {
    if (bar.enabled() && duration_s > 0) {
      bar.Update(NsToSeconds(run->last_stamp_ns - run->first_stamp_ns) / duration_s);
    }
    if (on_message) on_message(run);
  });
}

void CountMessage(MapRun* run, const Message& m) {
  if (m.kind == Message::Kind::kEvent) return;
  if (run->messages++ == 0) run->first_stamp_ns = m.stamp_ns;
  run->first_stamp_ns = std::min(run->first_stamp_ns, m.stamp_ns);
  run->last_stamp_ns = std::max(run->last_stamp_ns, m.stamp_ns);
  switch (m.kind) {
    case Message::Kind::kRadarScan:
      ++run->radar_messages;
      break;
    case Message::Kind::kOdometry:
      ++run->odometry_messages;
      break;
    case Message::Kind::kGroundTruth:
      run->ground_truth.push_back(m.odometry);
      break;
    case Message::Kind::kEvent:
      break;
  }
}

void FeedSlam(SlamSystem& slam, const Message& m) { FeedScanOrOdometry(slam, m); }

void Feed(MapRun* run, const Message& m) {
  CountMessage(run, m);
  FeedSlam(*run->slam, m);
}

AteResult TrajectoryError(const std::vector<std::pair<TimestampNs, Pose2>>& estimate,
                          const std::vector<OdometrySample>& reference, double max_dt_s,
                          bool align) {
  std::vector<OdometrySample> ref = reference;
  std::stable_sort(ref.begin(), ref.end(), [](const OdometrySample& a, const OdometrySample& b) {
    return a.stamp_ns < b.stamp_ns;
  });
  std::vector<Pose2> est_poses, ref_poses;
  const TimestampNs max_dt = SecondsToNs(max_dt_s);
  for (const auto& [stamp, pose] : estimate) {
    auto it =
        std::lower_bound(ref.begin(), ref.end(), stamp,
                         [](const OdometrySample& s, TimestampNs t) { return s.stamp_ns < t; });
    const OdometrySample* best = nullptr;
    TimestampNs best_dt = max_dt + 1;
    for (auto c : {it, it == ref.begin() ? it : it - 1}) {
      if (c == ref.end()) continue;
      const TimestampNs dt = std::llabs(c->stamp_ns - stamp);
      if (dt < best_dt) best_dt = dt, best = &*c;
    }
    if (best == nullptr || best_dt > max_dt) continue;
    est_poses.push_back(pose);
    ref_poses.push_back(best->T_world_robot);
  }
  if (est_poses.size() < 2) return AteResult{};
  return ComputeAte(est_poses, ref_poses, align);
}

std::vector<OdometrySample> ReadGroundTruthFile(const std::string& tum_path, double max_mb,
                                                std::vector<int>* lines) {
  return ReadTum(tum_path, max_mb, lines);
}

double PeakMemoryMiB() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;  // ru_maxrss is in KiB on Linux
}

}  // namespace uwbsar::slam
