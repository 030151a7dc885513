// Sessions (saved maps: docs/formats.md) on the long scenarios of docs/measurements.md: a saved
// map of run A, then run B of the same building (scene seed 1, noise seed s + 1 for A's
// s = 1, 3, 5; odometry starting at zero: its start pose unknown) joined to it (`map B
// --resume A`, the same MergeSessions as `merge`) and localised in it (`localize B --map A`).
//   seed_lab: A = the paper's depart-and-return (7.5 m); B starts 2 m further along
//             and 20 deg turned and drives 3 m out and back.
//   office:   A = route_loops.txt (74 m); B = route_ring_cw.txt (36 m); clearance 0.3 m.
// Counters (the acceptance figures): connected_after_m (B's path when placed), loops_between
// (accepted loops between the runs), false_loops (> 0.2 m or 5 deg from the truth),
// ate_common_cm (both runs after one alignment), ate_a_cm / ate_b_cm (each mapped alone),
// first_fix_m, false_fixes, ate_tracking_cm (localised keyframes), map_b_s / localize_b_s
// (wall clock of mapping / localising B, the simulator included in both), merge_s.
//
// Run by hand (about 1 minute per seed for seed_lab, 1-4 for office on 2 cores; not CI):
//   build/bin/uwbsar_bench --benchmark_filter=Session
#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include "backend/global_map.h"
#include "backend/trajectory_metrics.h"
#include "eval/compare/map_comparison.h"
#include "eval/compare/sar_image_occupancy.h"
#include "imaging/image_io.h"
#include "slam/localization/localize_job.h"
#include "slam/map_job.h"
#include "slam/outputs/map_outputs.h"
#include "slam/outputs/session_capture.h"
#include "slam/outputs/session_mosaic.h"
#include "slam/outputs/session_outputs.h"
#include "slam/scene_simulation.h"
#include "slam/session/session_merge.h"
#include "test/shared_data.h"

namespace uwbsar {
namespace {

constexpr double kFalseM = 0.2;
constexpr double kFalseDeg = 5.0;

struct Scenario {
  const char* name;
  std::string map_yaml;
  std::string route_a, route_b;
  Config config_a, config_b;
};

Scenario SeedLab() {
  Scenario s;
  s.name = "seed_lab";
  s.map_yaml = ::uwbsar::testing::SeedLabLidarMap();
  s.route_a = s.route_b = "depart-return";
  s.config_b.simulator.route.start_x_m += 2.0;
  s.config_b.simulator.route.start_yaw_deg += 20.0;
  s.config_b.simulator.route.depart_distance_m = 3.0;
  return s;
}

Scenario Office() {
  Scenario s;
  s.name = "office";
  const std::string dir = std::string(UWBSAR_SOURCE_DIR) + "/config/maps/office/";
  s.map_yaml = dir + "office.yaml";
  s.route_a = dir + "route_loops.txt";
  s.route_b = dir + "route_ring_cw.txt";
  s.config_a.simulator.route.clearance_m = 0.3;
  s.config_b = s.config_a;
  return s;
}

const OdometrySample& NearestTruth(const std::vector<OdometrySample>& gt, TimestampNs t) {
  const OdometrySample* best = &gt.front();
  for (const OdometrySample& g : gt) {
    if (std::llabs(g.stamp_ns - t) < std::llabs(best->stamp_ns - t)) best = &g;
  }
  return *best;
}

/// The true pose of a session keyframe's anchor (rigid to the robot at its stamp).
Pose2 TrueAnchor(const SessionKeyframe& k, const std::vector<OdometrySample>& gt) {
  return NearestTruth(gt, k.stamp_ns).T_world_robot * (k.T_odom_robot.Inverse() * k.T_odom_anchor);
}

bool IsFalse(const Pose2& estimate, const Pose2& truth) {
  const double err_m = std::hypot(estimate.x_m - truth.x_m, estimate.y_m - truth.y_m);
  const double err_deg = std::abs(NormalizeAngle(estimate.yaw_rad - truth.yaw_rad)) * 180 / M_PI;
  return err_m > kFalseM || err_deg > kFalseDeg;
}

/// `map` (on `grid`) scored against the LiDAR grid as `uwbsar compare` scores a map_float.tif
/// (ICP from `T_lidar_sar`; the occupancy rule of `map`).
MapMetrics ScoreMosaic(const cv::Mat& map, const ImageGrid& grid, const Config& config,
                       const std::string& grid_yaml, const std::string& name,
                       const Pose2& T_lidar_sar) {
  const std::string dir =
      (std::filesystem::temp_directory_path() / ("uwbsar_session_bench_" + name)).string();
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  WriteFloatTiff(dir + "/map_float.tif", map);
  std::ofstream(dir + "/map_grid.yaml") << slam::GridYaml(grid, name, "map_float.tif");
  AlignRequest request;
  request.T_lidar_sar = T_lidar_sar;
  const ComparisonReport report = CompareMapFiles(dir + "/map_grid.yaml", grid_yaml, request,
                                                  CompareConfig{}, SarOccupancyRuleOf(config.slam));
  std::filesystem::remove_all(dir);
  return report.comparison.metrics;
}

/// The session's map (the mosaic `map` / `map --resume` write) scored against the grid.
MapMetrics Score(const SessionData& session, const Config& config, const std::string& grid_yaml,
                 const std::string& name, const Pose2& T_lidar_sar = {}) {
  ImageGrid grid;
  cv::Mat observed;
  const cv::Mat map = slam::RenderSessionMosaic(session, config, &grid, &observed);
  return ScoreMosaic(map, grid, config, grid_yaml, name, T_lidar_sar);
}

/// The mosaic of `session` (every run), kept only where the tiles of run `trajectory` (at
/// their joined poses) observed, scored like Score: the joined map on one run's area.
MapMetrics ScoreOnRunArea(const SessionData& session, int trajectory, const Config& config,
                          const std::string& grid_yaml, const std::string& name) {
  const double res = config.slam.map_resolution_m;
  GlobalMap run(res);
  for (const SessionKeyframe& k : session.keyframes) {
    if (k.trajectory == trajectory) run.AddTile(k.detected.Load(), k.detected_grid, k.T_map_anchor);
  }
  ImageGrid grid, run_grid;
  cv::Mat observed, run_observed;
  cv::Mat map = slam::RenderSessionMosaic(session, config, &grid, &observed);
  run.Render(&run_grid, &run_observed);
  // Both on the world lattice: the run's canvas is a block-aligned part of the whole one.
  const int c0 = static_cast<int>(std::lround((run_grid.x0_m - grid.x0_m) / res));
  const int r0 = static_cast<int>(std::lround((grid.y0_m - run_grid.y0_m) / res));
  cv::Mat mask = cv::Mat::zeros(map.size(), CV_8UC1);
  run_observed.copyTo(mask(cv::Rect(c0, r0, run_grid.cols, run_grid.rows)));
  map.setTo(0.0f, ~mask);
  return ScoreMosaic(map, grid, config, grid_yaml, name, Pose2{});
}

std::string Describe(const MapMetrics& m) {
  char text[160];
  std::snprintf(text, sizeof text, "difference %.2f %%, F1 %.3f (P %.3f R %.3f) over %lld cells",
                m.difference_ratio * 100, m.f1, m.precision, m.recall, m.evaluated_cells);
  return text;
}

double Seconds(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

/// B joined to A (`map B --resume A`, `merge`): the merge and its figures against the truth.
struct ResumeFigures {
  MergeReport report;
  SessionData merged;
  double merge_s = 0.0;
  int between = 0, false_loops = 0;  ///< accepted loops between the runs; of them false
  AteResult common, ate_a, ate_b;    ///< both runs in the joined frame; each run alone
};

ResumeFigures Resume(const Config& config_a, const slam::MapRun& a, const SessionData& sa,
                     const slam::MapRun& b, const SessionData& sb) {
  ResumeFigures f;
  const auto t_merge = std::chrono::steady_clock::now();
  f.merged = MergeSessions(sa, sb, config_a, &f.report);
  f.merge_s = Seconds(t_merge);
  std::map<int, Pose2> truth;
  for (const SessionKeyframe& k : sa.keyframes) truth[k.id] = TrueAnchor(k, a.ground_truth);
  for (const SessionKeyframe& k : sb.keyframes) {
    truth[k.id + f.report.id_offset] = TrueAnchor(k, b.ground_truth);
  }
  for (const SessionLoop& l : f.merged.loops) {
    if (!l.accepted || l.reason != "between sessions") continue;
    ++f.between;
    f.false_loops += IsFalse(l.T_ij, Between(truth.at(l.match_id), truth.at(l.query_id)));
  }
  f.common = slam::CommonFrameError(
      f.merged, {{0, a.ground_truth}, {f.report.trajectory_offset, b.ground_truth}});
  f.ate_a = slam::TrajectoryError(a.slam->CorrectedTrajectory(), a.ground_truth);
  f.ate_b = slam::TrajectoryError(b.slam->CorrectedTrajectory(), b.ground_truth);
  return f;
}

/// The maps against the grid: A alone, B alone (its own frame: ICP from its start), both
/// joined, and the joined map on each run's own area (like for like).
struct MapScores {
  MapMetrics a, b, joined, joined_on_a, joined_on_b;
};

/// Scores and prints the maps; also prints the other joined mosaic and A's tiles alone at
/// their joined poses (what the joint optimisation moved, without B's tiles).
MapScores ScoreMaps(const Scenario& s, const std::string& label, const SessionData& sa,
                    const SessionData& sb, const ResumeFigures& r, const Pose2& T_odom_world_b) {
  const SessionData& merged = r.merged;
  const int b_id = r.report.trajectory_offset;
  MapScores m;
  m.a = Score(sa, s.config_a, s.map_yaml, "a");
  m.b = Score(sb, s.config_a, s.map_yaml, "b", T_odom_world_b.Inverse());
  m.joined = Score(merged, s.config_a, s.map_yaml, "joined");
  std::printf("%s maps vs the grid: A %s; B %s; joined %s\n", label.c_str(), Describe(m.a).c_str(),
              Describe(m.b).c_str(), Describe(m.joined).c_str());
  m.joined_on_a = ScoreOnRunArea(merged, 0, s.config_a, s.map_yaml, "on_a");
  m.joined_on_b = ScoreOnRunArea(merged, b_id, s.config_a, s.map_yaml, "on_b");
  std::printf("%s joined map on A's area: %s; on B's area: %s\n", label.c_str(),
              Describe(m.joined_on_a).c_str(), Describe(m.joined_on_b).c_str());
  for (const auto& [mode, mode_name] : EnumNames<JoinedMosaic>::kNames) {
    if (mode == s.config_a.session.joined_mosaic) continue;
    Config other = s.config_a;
    other.session.joined_mosaic = mode;
    std::printf("%s joined with session.joined_mosaic %s: %s; on A's area %s; on B's area %s\n",
                label.c_str(), mode_name,
                Describe(Score(merged, other, s.map_yaml, "joined")).c_str(),
                Describe(ScoreOnRunArea(merged, 0, other, s.map_yaml, "on_a")).c_str(),
                Describe(ScoreOnRunArea(merged, b_id, other, s.map_yaml, "on_b")).c_str());
  }
  SessionData a_joined = merged;
  a_joined.keyframes.clear();
  for (const SessionKeyframe& k : merged.keyframes) {
    if (k.trajectory == 0) a_joined.keyframes.push_back(k);
  }
  std::printf("%s A's tiles at the joined poses: %s\n", label.c_str(),
              Describe(Score(a_joined, s.config_a, s.map_yaml, "a_joined")).c_str());
  std::fflush(stdout);
  return m;
}

/// B localised in A's saved map (`localize B --map A`).
struct LocalizeFigures {
  slam::LocalizeRun loc;
  double wall_s = 0.0;  ///< with the simulator
  int fixes = 0, false_fixes = 0;
  AteResult ate_tracking;
};

LocalizeFigures LocalizeB(const Scenario& s, std::uint64_t seed, const slam::MapRun& a,
                          const SessionData& sa, const Pose2& T_odom_world_b) {
  LocalizeFigures f;
  const auto t_loc = std::chrono::steady_clock::now();
  f.loc =
      slam::LocalizeSimulation(sa, s.config_b, s.map_yaml, s.route_b, 1, seed + 1, T_odom_world_b);
  f.wall_s = Seconds(t_loc);
  const slam::LocalizeRun& loc = f.loc;
  // The map frame in the world: the best fit of all of A's keyframes (one keyframe's
  // heading error of 1 deg would move places 12 m away by 20 cm, the false-fix limit).
  std::vector<Pose2> map_anchors, true_anchors;
  for (const SessionKeyframe& k : sa.keyframes) {
    map_anchors.push_back(k.T_map_anchor);
    true_anchors.push_back(TrueAnchor(k, a.ground_truth));
  }
  const Pose2 T_world_map = ComputeAte(map_anchors, true_anchors).T_reference_estimate;
  for (const LocalizedKeyframe& k : loc.keyframes) {
    if (k.status == LocalizeStatus::kLost || k.loops == 0) continue;
    ++f.fixes;
    SessionKeyframe as_session;  // the localised keyframe's true anchor, as TrueAnchor
    as_session.stamp_ns = k.stamp_ns;
    as_session.T_odom_anchor = k.T_odom_anchor;
    const OdometryEntry* odom = &loc.odometry.front();
    for (const OdometryEntry& e : loc.odometry) {
      if (std::llabs(e.stamp_ns - k.stamp_ns) < std::llabs(odom->stamp_ns - k.stamp_ns)) odom = &e;
    }
    as_session.T_odom_robot = odom->T_world_robot;
    f.false_fixes +=
        IsFalse(T_world_map * k.T_map_anchor, TrueAnchor(as_session, loc.ground_truth));
  }
  f.ate_tracking = slam::TrajectoryError(loc.Trajectory(true), loc.ground_truth);
  return f;
}

void PrintResumeAndLocalize(const std::string& label, const slam::MapRun& a, const slam::MapRun& b,
                            const SessionData& sa, const ResumeFigures& r, const LocalizeFigures& l,
                            double map_b_wall_s) {
  const MergeReport& report = r.report;
  std::printf(
      "%s resume: %s after %.2f m of B, %d loops between the runs (%d rejected, %d dropped), "
      "%d false; ATE common frame %.2f cm (A alone %.2f, B alone %.2f; A's part of the "
      "joined map %.2f, B's %.2f; A alone from its own session the same way %.2f); merge "
      "%.2f s\n",
      label.c_str(), report.connected ? "connected" : "NOT connected", report.connect_path_m,
      r.between, report.loop_edges_rejected, report.dropped, r.false_loops, r.common.rmse_m * 100,
      r.ate_a.rmse_m * 100, r.ate_b.rmse_m * 100,
      slam::CommonFrameError(r.merged, {{0, a.ground_truth}}).rmse_m * 100,
      slam::CommonFrameError(r.merged, {{report.trajectory_offset, b.ground_truth}}).rmse_m * 100,
      slam::CommonFrameError(sa, {{0, a.ground_truth}}).rmse_m * 100, r.merge_s);
  std::printf(
      "%s localize: first fix after %.2f m, %zu keyframes, %d with fixes, %d false; ATE "
      "while tracking %.2f cm; wall clock with the simulator: %.2f s localising B vs %.2f s "
      "mapping B\n",
      label.c_str(), l.loc.first_fix >= 0 ? l.loc.first_fix_path_m : -1.0, l.loc.keyframes.size(),
      l.fixes, l.false_fixes, l.ate_tracking.rmse_m * 100, l.wall_s, map_b_wall_s);
  std::fflush(stdout);
}

void SetCounters(const ResumeFigures& r, const MapScores& m, const LocalizeFigures& l,
                 double map_b_wall_s, benchmark::State* state) {
  auto& c = state->counters;
  c["connected"] = r.report.connected;
  c["connected_after_m"] = r.report.connect_path_m;
  c["loops_between"] = r.between;
  c["false_loops"] = r.false_loops;
  c["ate_common_cm"] = r.common.rmse_m * 100;
  c["ate_a_cm"] = r.ate_a.rmse_m * 100;
  c["ate_b_cm"] = r.ate_b.rmse_m * 100;
  c["first_fix_m"] = l.loc.first_fix >= 0 ? l.loc.first_fix_path_m : -1.0;
  c["false_fixes"] = l.false_fixes;
  c["ate_tracking_cm"] = l.ate_tracking.rmse_m * 100;
  c["map_b_s"] = map_b_wall_s;
  c["localize_b_s"] = l.wall_s;
  c["merge_s"] = r.merge_s;
  c["diff_a_pct"] = m.a.difference_ratio * 100;
  c["diff_b_pct"] = m.b.difference_ratio * 100;
  c["diff_joined_pct"] = m.joined.difference_ratio * 100;
  c["f1_a"] = m.a.f1;
  c["f1_b"] = m.b.f1;
  c["f1_joined"] = m.joined.f1;
  c["diff_joined_on_a_pct"] = m.joined_on_a.difference_ratio * 100;
  c["diff_joined_on_b_pct"] = m.joined_on_b.difference_ratio * 100;
  c["f1_joined_on_a"] = m.joined_on_a.f1;
  c["f1_joined_on_b"] = m.joined_on_b.f1;
}

void BM_Session(benchmark::State& state) {
  const Scenario s = state.range(0) == 0 ? SeedLab() : Office();
  const std::uint64_t seed = static_cast<std::uint64_t>(state.range(1));  // A's; B's is seed + 1
  const std::string label = std::string(s.name) + " seed " + std::to_string(seed);
  if (!std::filesystem::exists(s.map_yaml)) {
    state.SkipWithError(("missing " + s.map_yaml).c_str());
    return;
  }
  const Pose2 T_odom_world_b = slam::RouteStart(s.config_b).Inverse();  // B's odometry from 0
  for (auto _ : state) {
    // Seed 1 is MapSimulation's (scene and noise from 1); others vary the noise of both runs
    // in the same scene.
    const slam::MapRun a =
        seed == 1 ? slam::MapSimulation(s.config_a, s.map_yaml, s.route_a, 1)
                  : slam::MapSimulationInScene(s.config_a, s.map_yaml, s.route_a, 1, seed);
    const auto t_map_b = std::chrono::steady_clock::now();
    const slam::MapRun b =
        slam::MapSimulationInScene(s.config_b, s.map_yaml, s.route_b, 1, seed + 1, T_odom_world_b);
    const double map_b_wall_s = Seconds(t_map_b);
    const SessionData sa = slam::CaptureSession(a);
    const SessionData sb = slam::CaptureSession(b);
    const ResumeFigures resume = Resume(s.config_a, a, sa, b, sb);
    const MapScores scores = ScoreMaps(s, label, sa, sb, resume, T_odom_world_b);
    const LocalizeFigures localize = LocalizeB(s, seed, a, sa, T_odom_world_b);
    PrintResumeAndLocalize(label, a, b, sa, resume, localize, map_b_wall_s);
    SetCounters(resume, scores, localize, map_b_wall_s, &state);
  }
}
BENCHMARK(BM_Session)->ArgsProduct({{0, 1}, {1, 3, 5}})->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace
}  // namespace uwbsar
