// Sessions (issue 18) on the long scenarios of README "Sessions": a saved map of run A,
// then run B of the same building (scene seed 1, noise seed 2, odometry starting at zero:
// its start pose unknown) joined to it (`map B --resume A`, the same MergeSessions as
// `merge`) and localised in it (`localize B --map A`).
//   seed_lab: A = the paper's depart-and-return (7.5 m, seed 1); B starts 2 m further along
//             and 20 deg turned and drives 3 m out and back.
//   office:   A = route_loops.txt (74 m); B = route_ring_cw.txt (36 m); clearance 0.3 m.
// Counters (the acceptance figures): connected_after_m (B's path when placed), loops_between
// (accepted loops between the runs), false_loops (> 0.2 m or 5 deg from the truth),
// ate_common_cm (both runs after one alignment), ate_a_cm / ate_b_cm (each mapped alone),
// first_fix_m, false_fixes, ate_tracking_cm (localised keyframes), map_b_s / localize_b_s
// (wall clock of mapping / localising B, the simulator included in both), merge_s.
//
// Run by hand (about 1 minute for seed_lab, 3-4 for office on 2 cores; not part of CI):
//   build/bin/uwbsar_bench --benchmark_filter=Session
#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>

#include "pipeline/localize_job.h"
#include "pipeline/map_job.h"
#include "pipeline/scene_simulation.h"
#include "pipeline/session_capture.h"
#include "pipeline/session_outputs.h"
#include "session/session_merge.h"
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

double Seconds(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

void BM_Session(benchmark::State& state) {
  const Scenario s = state.range(0) == 0 ? SeedLab() : Office();
  if (!std::filesystem::exists(s.map_yaml)) {
    state.SkipWithError(("missing " + s.map_yaml).c_str());
    return;
  }
  const Pose2 T_odom_world_b = tools::RouteStart(s.config_b).Inverse();  // B's odometry from 0
  for (auto _ : state) {
    const tools::MapRun a = tools::MapSimulation(s.config_a, s.map_yaml, s.route_a, 1);
    const auto t_map_b = std::chrono::steady_clock::now();
    const tools::MapRun b =
        tools::MapSimulationInScene(s.config_b, s.map_yaml, s.route_b, 1, 2, T_odom_world_b);
    const double map_b_wall_s = Seconds(t_map_b);
    const SessionData sa = tools::CaptureSession(a);
    const SessionData sb = tools::CaptureSession(b);

    // Resume / merge: B joined to A.
    const auto t_merge = std::chrono::steady_clock::now();
    MergeReport report;
    const SessionData merged = MergeSessions(sa, sb, s.config_a, &report);
    const double merge_s = Seconds(t_merge);
    std::map<int, Pose2> truth;
    for (const SessionKeyframe& k : sa.keyframes) truth[k.id] = TrueAnchor(k, a.ground_truth);
    for (const SessionKeyframe& k : sb.keyframes) {
      truth[k.id + report.id_offset] = TrueAnchor(k, b.ground_truth);
    }
    int between = 0, false_loops = 0;
    for (const SessionLoop& l : merged.loops) {
      if (!l.accepted || l.reason != "between sessions") continue;
      ++between;
      false_loops += IsFalse(l.T_ij, Between(truth.at(l.match_id), truth.at(l.query_id)));
    }
    const AteResult common = tools::CommonFrameError(
        merged, {{0, a.ground_truth}, {report.trajectory_offset, b.ground_truth}});
    const AteResult ate_a = tools::TrajectoryError(a.slam->CorrectedTrajectory(), a.ground_truth);
    const AteResult ate_b = tools::TrajectoryError(b.slam->CorrectedTrajectory(), b.ground_truth);

    // Localise B in A.
    const auto t_loc = std::chrono::steady_clock::now();
    const tools::LocalizeRun loc =
        tools::LocalizeSimulation(sa, s.config_b, s.map_yaml, s.route_b, 1, 2, T_odom_world_b);
    const double localize_b_wall_s = Seconds(t_loc);
    const SessionKeyframe& k0 = sa.keyframes.front();
    const Pose2 T_world_map = TrueAnchor(k0, a.ground_truth) * k0.T_map_anchor.Inverse();
    int fixes = 0, false_fixes = 0;
    for (const LocalizedKeyframe& k : loc.keyframes) {
      if (k.status == LocalizeStatus::kLost || k.loops == 0) continue;
      ++fixes;
      SessionKeyframe as_session;  // the localised keyframe's true anchor, as TrueAnchor
      as_session.stamp_ns = k.stamp_ns;
      as_session.T_odom_anchor = k.T_odom_anchor;
      const OdometryEntry* odom = &loc.odometry.front();
      for (const OdometryEntry& e : loc.odometry) {
        if (std::llabs(e.stamp_ns - k.stamp_ns) < std::llabs(odom->stamp_ns - k.stamp_ns))
          odom = &e;
      }
      as_session.T_odom_robot = odom->T_world_robot;
      false_fixes +=
          IsFalse(T_world_map * k.T_map_anchor, TrueAnchor(as_session, loc.ground_truth));
    }
    const AteResult ate_tracking = tools::TrajectoryError(loc.Trajectory(true), loc.ground_truth);

    std::printf(
        "%s resume: %s after %.2f m of B, %d loops between the runs (%d rejected, %d dropped), "
        "%d false; ATE common frame %.2f cm (A alone %.2f, B alone %.2f); merge %.2f s\n",
        s.name, report.connected ? "connected" : "NOT connected", report.connect_path_m, between,
        report.loop_edges_rejected, report.dropped, false_loops, common.rmse_m * 100,
        ate_a.rmse_m * 100, ate_b.rmse_m * 100, merge_s);
    std::printf(
        "%s localize: first fix after %.2f m, %zu keyframes, %d with fixes, %d false; ATE "
        "while tracking %.2f cm; wall clock with the simulator: %.2f s localising B vs %.2f s "
        "mapping B\n",
        s.name, loc.first_fix >= 0 ? loc.first_fix_path_m : -1.0, loc.keyframes.size(), fixes,
        false_fixes, ate_tracking.rmse_m * 100, localize_b_wall_s, map_b_wall_s);
    std::fflush(stdout);
    state.counters["connected"] = report.connected;
    state.counters["connected_after_m"] = report.connect_path_m;
    state.counters["loops_between"] = between;
    state.counters["false_loops"] = false_loops;
    state.counters["ate_common_cm"] = common.rmse_m * 100;
    state.counters["ate_a_cm"] = ate_a.rmse_m * 100;
    state.counters["ate_b_cm"] = ate_b.rmse_m * 100;
    state.counters["first_fix_m"] = loc.first_fix >= 0 ? loc.first_fix_path_m : -1.0;
    state.counters["false_fixes"] = false_fixes;
    state.counters["ate_tracking_cm"] = ate_tracking.rmse_m * 100;
    state.counters["map_b_s"] = map_b_wall_s;
    state.counters["localize_b_s"] = localize_b_wall_s;
    state.counters["merge_s"] = merge_s;
  }
}
BENCHMARK(BM_Session)->Arg(0)->Arg(1)->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace
}  // namespace uwbsar
