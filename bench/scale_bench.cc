// Scale benchmark: a simulated 1 km run of repeated loops through
// a 50 m x 50 m floor (config/maps/floor50), streamed from the simulator into SlamSystem in
// memory (no scan is held by the harness). Requirements: peak memory <= 4 GB, and SLAM
// processing time per metre over the last 100 m within 1.5x that of the first 100 m.
//
// Run by hand (about 10-20 minutes on 2 cores; not part of CI):
//   build/bin/uwbsar_bench --benchmark_filter=Scale
// A table on stdout gives, per 100 m of odometry path, the SLAM time per metre by stage,
// keyframes, loops and the resident memory (VmRSS), so growth can be traced to a stage.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "bench/resident_memory.h"
#include "slam/app_config.h"
#include "slam/map_job.h"

namespace uwbsar {
namespace {

std::string Floor50File(const std::string& name) {
  return std::string(UWBSAR_SOURCE_DIR) + "/config/maps/floor50/" + name;
}

/// The state of the run when the odometry path first reached a whole metre.
struct Sample {
  double path_m = 0.0;
  slam::StageTimes times;
  std::size_t keyframes = 0;
  std::size_t loops = 0;
  int validated = 0;              ///< loops the validator accepted so far
  double odometry_error_m = 0.0;  ///< |odometry - truth| position now (not aligned)
  double rss_mib = 0.0;
};

double Total(const slam::StageTimes& t) {
  return t.imaging_s + t.features_s + t.matching_s + t.optimization_s;
}

/// SLAM seconds per metre between two samples, per stage and in total.
struct Window {
  double total = 0.0, imaging = 0.0, features = 0.0, matching = 0.0, optimization = 0.0;
};
Window PerMetre(const Sample& a, const Sample& b) {
  const double m = b.path_m - a.path_m;
  return {(Total(b.times) - Total(a.times)) / m, (b.times.imaging_s - a.times.imaging_s) / m,
          (b.times.features_s - a.times.features_s) / m,
          (b.times.matching_s - a.times.matching_s) / m,
          (b.times.optimization_s - a.times.optimization_s) / m};
}

/// Maps the 1 km run, taking a Sample each time the odometry path reaches a whole metre.
slam::MapRun RunSampled(const Config& config, std::vector<Sample>* samples,
                        std::map<int, Pose2>* true_anchor) {
  std::vector<OdometrySample> ground_truth;
  long long ground_truth_seen = 0;
  slam::MapRun run = slam::MapSimulation(
      config, Floor50File("floor50.yaml"), Floor50File("route_1km.txt"), /*seed=*/1,
      [&](slam::MapRun* r) {
        // Ground truth comes at 200 Hz; keep 50 Hz (the odometry rate) for the ATE so the
        // harness itself stays small.
        for (const OdometrySample& g : r->ground_truth) {
          if (ground_truth_seen++ % 4 == 0) ground_truth.push_back(g);
        }
        r->ground_truth.clear();
        // The keyframe thread writes what is read below.
        const auto state = r->slam->LockState();
        const auto& odometry = r->slam->odometry();
        if (odometry.empty()) return;
        // Each keyframe's true anchor as it appears (a revisit may retire it later): the
        // anchor is rigidly attached to the robot at the keyframe's stamp.
        for (const slam::KeyframeRecord& k : r->slam->keyframes()) {
          if (ground_truth.empty() || true_anchor->count(k.keyframe.id)) continue;
          auto it = std::lower_bound(
              ground_truth.begin(), ground_truth.end(), k.keyframe.stamp_ns,
              [](const OdometrySample& g, TimestampNs t) { return g.stamp_ns < t; });
          if (it == ground_truth.end()) --it;
          (*true_anchor)[k.keyframe.id] =
              it->T_world_robot * (k.keyframe.T_world_robot.Inverse() * k.keyframe.T_world_anchor);
        }
        const double path_m = odometry.back().path_m;
        if (!samples->empty() && path_m < samples->back().path_m + 1.0) return;
        Sample s;
        s.path_m = path_m;
        s.times = r->slam->times();
        s.keyframes = r->slam->keyframes().size();
        s.loops = r->slam->loops().size();
        for (const slam::LoopRecord& l : r->slam->loops()) s.validated += l.validation.accepted;
        if (!ground_truth.empty()) {
          const Pose2& truth = ground_truth.back().T_world_robot;
          const Pose2& odom = odometry.back().T_world_robot;
          s.odometry_error_m = std::hypot(odom.x_m - truth.x_m, odom.y_m - truth.y_m);
        }
        s.rss_mib = samples->size() % 10 == 0 ? ResidentMiB() : samples->back().rss_mib;
        samples->push_back(s);
      });
  run.ground_truth = std::move(ground_truth);
  return run;
}

/// The table on stdout: per 100 m, SLAM time per metre by stage, keyframes, loops, memory.
void PrintPerHundredMetres(const std::vector<Sample>& samples) {
  std::printf("%8s %9s %9s %9s %9s %9s %9s %7s %9s %10s %9s\n", "path_m", "ms/m", "imaging",
              "features", "matching", "optimise", "keyframes", "loops", "validated", "odom_err_m",
              "VmRSS_MiB");
  for (std::size_t i = 0; i + 100 < samples.size(); i += 100) {
    const Window w = PerMetre(samples[i], samples[i + 100]);
    const Sample& b = samples[i + 100];
    std::printf("%8.0f %9.2f %9.2f %9.2f %9.2f %9.2f %9zu %7zu %9d %10.2f %9.0f\n", b.path_m,
                w.total * 1e3, w.imaging * 1e3, w.features * 1e3, w.matching * 1e3,
                w.optimization * 1e3, b.keyframes, b.loops, b.validated, b.odometry_error_m,
                b.rss_mib);
  }
}

/// The first 100 m and the last 100 m of the run, per metre.
std::pair<Window, Window> FirstAndLastHundredMetres(const std::vector<Sample>& samples) {
  const Sample& first = samples.front();
  const Sample* at100 = &samples.front();
  for (const Sample& s : samples) {
    if (s.path_m - first.path_m >= 100.0) {
      at100 = &s;
      break;
    }
  }
  const Sample& last = samples.back();
  const Sample* last100 = &last;
  for (auto it = samples.rbegin(); it != samples.rend(); ++it) {
    if (last.path_m - it->path_m >= 100.0) {
      last100 = &*it;
      break;
    }
  }
  return {PerMetre(first, *at100), PerMetre(*last100, last)};
}

/// Accepted loops, and those more than 0.2 m or 5 deg from the truth (true anchors recorded
/// as the keyframes appeared).
std::pair<int, int> CountLoops(const slam::MapRun& run, std::map<int, Pose2> true_anchor) {
  int accepted = 0, false_accepted = 0;
  for (const slam::LoopRecord& l : run.slam->loops()) {
    if (!l.accepted()) continue;
    ++accepted;
    const Pose2 truth = Between(true_anchor[l.match_id], true_anchor[l.query_id]);
    const Pose2& T = l.validation.constraint.T_ij;
    false_accepted += std::hypot(T.x_m - truth.x_m, T.y_m - truth.y_m) > 0.2 ||
                      std::abs(NormalizeAngle(T.yaw_rad - truth.yaw_rad)) > 5.0 * M_PI / 180.0;
  }
  return {accepted, false_accepted};
}

/// What SlamSystem holds per keyframe: the detected tile at map resolution, and the range
/// profiles of the scans it imaged (shared between overlapping tiles).
void CountHeldBytes(const slam::MapRun& run, benchmark::State& state) {
  double detected_bytes = 0.0, profile_bytes = 0.0;
  std::set<const RangeProfile*> profiles;
  for (const slam::KeyframeRecord& k : run.slam->keyframes()) {
    const cv::Mat detected = k.detected.Load();
    detected_bytes += static_cast<double>(detected.total() * detected.elemSize());
    for (const ImagedScan& scan : k.keyframe.scans) {
      if (scan.profile && profiles.insert(scan.profile.get()).second) {
        profile_bytes += static_cast<double>(
            (scan.profile->real.capacity() + scan.profile->imag.capacity()) * sizeof(float));
      }
    }
  }
  state.counters["detected_MiB"] = detected_bytes / (1 << 20);
  state.counters["profiles_MiB"] = profile_bytes / (1 << 20);
  state.counters["profiles_held"] = static_cast<double>(profiles.size());
}

/// ATE of SLAM and of the odometry against the run's ground truth.
std::pair<AteResult, AteResult> Errors(const slam::MapRun& run) {
  std::vector<std::pair<TimestampNs, Pose2>> odometry;
  for (const OdometryEntry& e : run.slam->odometry()) {
    odometry.push_back({e.stamp_ns, e.T_world_robot});
  }
  return {slam::TrajectoryError(run.slam->CorrectedTrajectory(), run.ground_truth),
          slam::TrajectoryError(odometry, run.ground_truth)};
}

void BM_ScaleFloor50OneKm(benchmark::State& state) {
  const Config config;
  for (auto _ : state) {
    std::vector<Sample> samples;  // one per metre of odometry path
    std::map<int, Pose2> true_anchor;
    const slam::MapRun run = RunSampled(config, &samples, &true_anchor);
    if (samples.size() < 201) {
      state.SkipWithError("the run is shorter than 200 m");
      return;
    }
    const auto [w_first, w_last] = FirstAndLastHundredMetres(samples);
    PrintPerHundredMetres(samples);
    // Memory growth per keyframe over the second half (after the allocator has warmed up).
    const Sample& mid = samples[samples.size() / 2];
    const Sample& last = samples.back();
    const double growth_kib =
        (last.rss_mib - mid.rss_mib) * 1024.0 /
        static_cast<double>(std::max<std::size_t>(1, last.keyframes - mid.keyframes));
    const auto [ate, odom] = Errors(run);
    const auto [accepted, false_accepted] = CountLoops(run, true_anchor);
    CountHeldBytes(run, state);

    state.counters["travel_m"] = last.path_m;
    state.counters["peak_rss_MiB"] = slam::PeakMemoryMiB();
    state.counters["first100_ms_per_m"] = w_first.total * 1e3;
    state.counters["last100_ms_per_m"] = w_last.total * 1e3;
    state.counters["last_over_first"] = w_last.total / w_first.total;
    state.counters["rss_KiB_per_keyframe"] = growth_kib;
    state.counters["keyframes"] = static_cast<double>(run.slam->keyframes().size());
    state.counters["keyframes_retired"] = static_cast<double>(run.slam->retired().size());
    state.counters["loops_accepted"] = accepted;
    state.counters["false_loops_accepted"] = false_accepted;
    state.counters["candidates"] = static_cast<double>(run.slam->loops().size());
    state.counters["ate_cm"] = ate.rmse_m * 100.0;
    state.counters["odometry_ate_cm"] = odom.rmse_m * 100.0;
    state.counters["slam_s"] = run.processing_s;
    state.counters["real_time_factor"] = run.log_duration_s() / run.processing_s;
    state.counters["finish_s"] = run.processing_s - Total(last.times);
  }
}
BENCHMARK(BM_ScaleFloor50OneKm)->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace
}  // namespace uwbsar
