#include "slam/outputs/results_timeline.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "slam/outputs/navigation_map.h"
#include "slam/outputs/session_mosaic.h"
#include "slam/outputs/session_outputs.h"
#include "slam/outputs/session_report.h"

namespace uwbsar::slam {
namespace {

using StampedPoses = std::vector<std::pair<TimestampNs, Pose2>>;

/// A pose every kResultsPathSpacingM of travel along `poses`, and the last one.
StampedPoses Thinned(const StampedPoses& poses) {
  StampedPoses out;
  double since_m = 0.0;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    if (i > 0) {
      since_m += std::hypot(poses[i].second.x_m - poses[i - 1].second.x_m,
                            poses[i].second.y_m - poses[i - 1].second.y_m);
    }
    if (i == 0 || i + 1 == poses.size() || since_m >= kResultsPathSpacingM) {
      out.push_back(poses[i]);
      since_m = 0.0;
    }
  }
  return out;
}

StampedPoses Stamped(const std::vector<OdometrySample>& samples) {
  StampedPoses out;
  out.reserve(samples.size());
  for (const OdometrySample& s : samples) out.push_back({s.stamp_ns, s.T_world_robot});
  return out;
}

/// /tf for odometry samples `odom` and their map-frame poses `corrected` (1:1), at most every
/// kResultsTfPeriodS, up to and including `until`; `next` is the first sample not yet looked
/// at and `next_stamp` the earliest stamp the next /tf may have.
struct TfWriter {
  const StampedPoses* odom = nullptr;
  const StampedPoses* corrected = nullptr;
  std::size_t next = 0;
  TimestampNs next_stamp = 0;
  bool started = false;

  void WriteUntil(TimestampNs until, ResultsMcapWriter* out) {
    for (; next < odom->size() && (*odom)[next].first <= until; ++next) {
      const auto& [stamp, T_odom_robot] = (*odom)[next];
      if (started && stamp < next_stamp) continue;
      out->WriteTf(stamp, (*corrected)[next].second * T_odom_robot.Inverse(), T_odom_robot);
      next_stamp = stamp + static_cast<TimestampNs>(kResultsTfPeriodS * 1e9);
      started = true;
    }
  }
};

/// The accepted loops as lines; every keyframe's anchor.
void WriteRunLoops(const SlamSnapshot& s, TimestampNs stamp, ResultsMcapWriter* out) {
  std::vector<Point2> anchors;
  for (const TileSnapshot& t : s.tiles) {
    const Pose2& p = s.poses.at(t.id);
    anchors.push_back({p.x_m, p.y_m});
  }
  out->WriteLoops(stamp, s.AcceptedLoopSegments(), anchors);
}

/// /map, /path and /uwbsar/loops of the state `s` at `stamp`; `inputs` gathered from the run.
void WriteRunState(const SlamSnapshot& s, const RunNavigationInputs& inputs, TimestampNs stamp,
                   ResultsMcapWriter* out) {
  const StampedPoses corrected = s.CorrectedTrajectory();
  out->WriteMap(stamp, RunNavigationGrid(s, inputs, corrected));
  out->WritePath(kResultsPathTopic, stamp, Thinned(corrected));
  WriteRunLoops(s, stamp, out);
}

}  // namespace

void WriteRunResultsMcap(const std::string& path, const SlamSnapshot& slam,
                         const std::vector<OdometrySample>& ground_truth, const SarMosaic& sar) {
  ResultsMcapWriter out(path);
  if (slam.odometry.empty() || slam.tiles.empty()) return out.Close();
  StampedPoses odom;
  for (const OdometryEntry& e : slam.odometry) odom.push_back({e.stamp_ns, e.T_world_robot});
  const StampedPoses corrected = slam.CorrectedTrajectory();
  TfWriter tf{&odom, &corrected};
  const RunNavigationInputs inputs = GatherRunNavigationInputs(slam);  // once for every solve
  const TimestampNs first = odom.front().first;
  TimestampNs last = odom.back().first;
  if (!ground_truth.empty()) {
    out.WritePath(kResultsGroundTruthTopic, first, Thinned(Stamped(ground_truth)));
  }
  bool final_state_written = false;
  for (std::size_t i = 0; i < slam.solves.size(); ++i) {
    const SolveRecord& solve = slam.solves[i];
    tf.WriteUntil(solve.stamp_ns, &out);
    WriteRunState(slam.AfterSolve(i), inputs, solve.stamp_ns, &out);
    last = std::max(last, solve.stamp_ns);
    final_state_written = solve.ids.size() == slam.tiles.size() && slam.retired.empty() &&
                          solve.num_odometry == slam.odometry.size() &&
                          solve.num_loops == slam.loops.size();
  }
  tf.WriteUntil(last, &out);
  if (!final_state_written) WriteRunState(slam, inputs, last, &out);
  out.WriteSar(last, MakeSarPreview(sar, slam.config->slam.results_mcap_sar_max_pixels));
  out.Close();
}

void WriteSessionResultsMcap(const std::string& path, const SessionData& session,
                             const Config& config, const OccupancyGrid& grid, const SarMosaic& sar,
                             const std::map<int, std::vector<OdometrySample>>& ground_truth) {
  ResultsMcapWriter out(path);
  if (session.trajectories.empty()) return out.Close();
  const int newest = session.trajectories.back().id;
  StampedPoses odom;
  for (const SessionOdometry& o : session.odometry) {
    if (o.trajectory == newest) odom.push_back({o.stamp_ns, o.T_odom_robot});
  }
  if (odom.empty()) return out.Close();
  const TimestampNs first = odom.front().first;
  out.WriteMap(first, grid);
  out.WriteSar(first, MakeSarPreview(sar, config.slam.results_mcap_sar_max_pixels));
  const auto truth = ground_truth.find(newest);
  if (truth != ground_truth.end() && !truth->second.empty()) {
    out.WritePath(kResultsGroundTruthTopic, first, Thinned(Stamped(truth->second)));
  }
  StampedPoses newest_corrected;
  for (const SessionTrajectory& t : session.trajectories) {
    StampedPoses corrected = CorrectedTrajectory(session, t.id);
    out.WritePath("/uwbsar/run_" + std::to_string(t.id) + "/path", first, Thinned(corrected));
    if (t.id == newest) newest_corrected = std::move(corrected);
  }
  out.WritePath(kResultsPathTopic, first, Thinned(newest_corrected));
  std::vector<Point2> anchors;
  for (const SessionKeyframe& k : session.keyframes) {
    anchors.push_back({k.T_map_anchor.x_m, k.T_map_anchor.y_m});
  }
  out.WriteLoops(first, SessionLoopSegments(session), anchors);
  TfWriter tf{&odom, &newest_corrected};
  tf.WriteUntil(odom.back().first, &out);
  out.Close();
}

void WriteLocalizeResultsMcap(const std::string& path, const LocalizeRun& run,
                              const SessionData& map, const Config& config,
                              const OccupancyGrid& map_grid) {
  ResultsMcapWriter out(path);
  if (run.odometry.empty()) return out.Close();
  const TimestampNs first = run.odometry.front().stamp_ns;
  out.WriteMap(first, map_grid);
  SarMosaic sar;
  sar.map = RenderSessionMosaic(map, config, &sar.grid, &sar.observed);
  out.WriteSar(first, MakeSarPreview(sar, config.slam.results_mcap_sar_max_pixels));
  if (!run.ground_truth.empty()) {
    out.WritePath(kResultsGroundTruthTopic, first, Thinned(Stamped(run.ground_truth)));
  }
  // From the first fix on, as trajectory.tum: before it the robot was not placed in the map.
  const StampedPoses all = run.Trajectory(false);  // every sample once placed, else none
  if (all.size() != run.odometry.size()) return out.Close();
  StampedPoses odom, corrected;
  for (std::size_t i = 0; i < all.size(); ++i) {
    if (all[i].first < run.first_fix_stamp_ns) continue;
    odom.push_back({run.odometry[i].stamp_ns, run.odometry[i].T_world_robot});
    corrected.push_back(all[i]);
  }
  if (odom.empty()) return out.Close();
  TfWriter tf{&odom, &corrected};
  tf.WriteUntil(odom.back().first, &out);
  out.WritePath(kResultsPathTopic, odom.back().first, Thinned(corrected));
  out.Close();
}

}  // namespace uwbsar::slam
