// SlamSnapshot: a copy of what SlamSystem's outputs are made from (keyframe poses and
// tiles, loop records, graph edges, odometry, counters), taken under LockState() in time
// linear in the keyframes, loops and odometry samples (plain copies: no rendering, no
// I/O). The tiles' detected images are shared, not copied: SlamSystem never writes a
// tile after the keyframe is stored, so the snapshot may read them without the lock.
// A live snapshot writer takes one under the lock, releases it and then renders and
// writes from the copy while the keyframe thread goes on.
#pragma once

#include <map>
#include <utility>
#include <vector>

#include "backend/pose_graph.h"
#include "core/pose2.h"
#include "core/types.h"
#include "frontend/imaging_frontend.h"
#include "frontend/odometry_buffer.h"
#include "frontend/place_recognition/place_recognizer.h"
#include "slam/app_config.h"
#include "slam/session/tile_store.h"

namespace uwbsar::slam {

/// Every candidate pair that was matched, with the outcome.
struct LoopRecord {
  int query_id = 0;     ///< the new keyframe (j)
  int match_id = 0;     ///< the earlier keyframe (i)
  bool guided = false;  ///< a pair of the guided pass around a validated loop

  /// Matched radar by radar (frontend/place_recognition/radar_match.h).
  bool by_radar = false;
  DetectorMap<MatchResult> matches;  ///< per detector of the validation pair (decision only)
  LoopValidation validation;
  int edge_index = -1;  ///< pose-graph edge, when the validator accepted it
  bool rejected_by_backend = false;
  double chi2 = 0.0;  ///< of the edge at the final solution
  bool accepted() const { return validation.accepted && !rejected_by_backend; }
  /// The match of `kind` (an empty result when that detector was not run).
  const MatchResult& Match(DetectorKind kind) const;
};

/// One keyframe as the outputs need it.
struct TileSnapshot {
  int id = 0;
  TimestampNs stamp_ns = 0;
  Pose2 T_world_anchor;  ///< odometry pose of the tile frame
  TileRef detected;      ///< shared, read-only (see above); Load() reads it back
  ImageGrid detected_grid;
  bool has_scans = false;  ///< first/last_scan_ns are valid
  TimestampNs first_scan_ns = 0, last_scan_ns = 0;
};

/// Seconds spent per stage (wall clock; imaging on the feeding thread, the rest on
/// the keyframe thread when there is one).
struct StageTimes {
  double imaging_s = 0.0;       ///< gating, range compression, back-projection
  double features_s = 0.0;      ///< feature images and AKAZE + ORB detection
  double matching_s = 0.0;      ///< candidate search, matching and validation
  double optimization_s = 0.0;  ///< pose-graph solves
};

/// The graph after one solve, kept with slam.results_mcap: results.mcap replays the map and
/// path as they were after each solve. The keyframes `ids` (those still kept then), the first
/// num_odometry odometry samples and num_loops loop records existed then.
struct SolveRecord {
  TimestampNs stamp_ns = 0;  ///< the latest odometry sample handed over by then
  std::size_t num_odometry = 0, num_loops = 0;
  std::vector<int> ids;      ///< the keyframes in the graph then, in order
  std::vector<Pose2> poses;  ///< their optimised T_world_anchor
};

/// A keyframe as the trajectory's correction needs it: when it was, where odometry put its
/// anchor and where the map puts it now. Kept keyframes and retired ones
/// (slam/session/place_views.h) alike: a retired keyframe follows the node it was folded into.
struct TrajectoryAnchor {
  int id = 0;
  TimestampNs stamp_ns = 0;
  Pose2 T_odom_anchor;   ///< odometry pose of the tile frame
  Pose2 T_world_anchor;  ///< optimised
};

/// A keyframe the map retired (slam/session/place_views.h): what places its run's trajectory.
struct RetiredKeyframe {
  int id = 0;
  TimestampNs stamp_ns = 0;
  Pose2 T_odom_anchor;  ///< odometry pose of the tile frame
  Pose2 T_odom_robot;   ///< odometry pose of the robot at stamp_ns
  double path_begin_m = 0.0, path_end_m = 0.0;
  int hub_id = -1;     ///< the node it was folded into (PoseGraph::RemoveNode); -1: none
  Pose2 T_hub_anchor;  ///< its pose in the hub's frame then (absolute when hub_id is -1)
};

/// The optimised pose of every retired keyframe from the poses of the kept ones: through its
/// hub, or its hub's hub when that was retired later. Retired keyframes whose chain reaches no
/// pose in `poses` are left out.
std::map<int, Pose2> RetiredPoses(const std::vector<RetiredKeyframe>& retired,
                                  const std::map<int, Pose2>& poses);

/// `kept` and `retired` merged into one list in time order.
std::vector<TrajectoryAnchor> MergeAnchors(std::vector<TrajectoryAnchor> kept,
                                           const std::vector<TrajectoryAnchor>& retired);

/// The correction T_world_corrected * T_world_odom^-1 at a time from anchors in time order.
Pose2 CorrectionAt(const std::vector<TrajectoryAnchor>& anchors, TimestampNs stamp_ns);

/// The correction T_world_corrected * T_world_odom^-1 at a time, interpolated between the
/// keyframes around it; `stamp(i)`, `anchor(i)` and `pose(i)` (the optimised anchor) of
/// keyframe i of `n`, in time order. Shared by SlamSystem and SlamSnapshot.
template <class Stamp, class Anchor, class Optimised>
Pose2 InterpolatedCorrection(std::size_t n, const Stamp& stamp, const Anchor& anchor,
                             const Optimised& pose, TimestampNs stamp_ns) {
  if (n == 0) return Pose2{};
  auto correction = [&](std::size_t i) { return pose(i) * anchor(i).Inverse(); };
  std::size_t lo = 0, hi = n;  // first keyframe with stamp >= stamp_ns
  while (lo < hi) {
    const std::size_t mid = (lo + hi) / 2;
    if (stamp(mid) < stamp_ns) {
      lo = mid + 1;
    } else {
      hi = mid;
    }
  }
  if (lo == 0) return correction(0);
  if (lo == n) return correction(n - 1);
  const std::size_t i = lo;
  const TimestampNs t0 = stamp(i - 1), t1 = stamp(i);
  const double t =
      t1 > t0 ? static_cast<double>(stamp_ns - t0) / static_cast<double>(t1 - t0) : 0.0;
  // Interpolate the two corrections as rotations about the earlier anchor, not about the
  // world origin: a correction's translation depends on its pivot, and with a pivot far
  // away (a map frame 1e6 m from the robot) the linear blend of translations would move
  // the samples between keyframes by metres. About a nearby pivot the result does not
  // depend on where the world origin is.
  const Pose2& a = anchor(i - 1);
  const Pose2 to_pivot{-a.x_m, -a.y_m, 0.0}, from_pivot{a.x_m, a.y_m, 0.0};
  const Pose2 blend = Interpolate(to_pivot * correction(i - 1) * from_pivot,
                                  to_pivot * correction(i) * from_pivot, t);
  return from_pivot * blend * to_pivot;
}

struct SlamSnapshot {
  const Config* config = nullptr;  ///< the SlamSystem's (lives as long as it does)
  std::vector<SensorGeometry> sensors;
  std::vector<TileSnapshot> tiles;        ///< keyframes in order (those the map keeps)
  std::map<int, Pose2> poses;             ///< optimised T_world_anchor by keyframe id
  std::vector<TrajectoryAnchor> retired;  ///< retired keyframes (slam/session/place_views.h), in
                                          ///< time order, at their optimised poses
  std::vector<PoseGraphEdge> edges;
  std::vector<int> fixed_ids;
  std::vector<LoopRecord> loops;
  std::vector<OdometryEntry> odometry;
  FrontendStats frontend_stats;
  StageTimes times;
  OptimizeResult last_optimization;
  int num_solves = 0;               ///< pose-graph solves so far
  std::vector<SolveRecord> solves;  ///< every solve, in order (slam.results_mcap; else empty)

  /// The detectors the loops were validated with (place_recognition.validation.detectors;
  /// the default pair without a configuration).
  std::vector<DetectorKind> LoopDetectors() const;
  /// Kept and retired keyframes in time order (what the correction interpolates).
  std::vector<TrajectoryAnchor> Anchors() const;
  /// As SlamSystem::CorrectionAt / CorrectedTrajectory, from the copy.
  Pose2 CorrectionAt(TimestampNs stamp_ns) const;
  std::vector<std::pair<TimestampNs, Pose2>> CorrectedTrajectory() const;
  /// The accepted loops whose two keyframes have poses, as segments between those poses.
  std::vector<std::pair<Point2, Point2>> AcceptedLoopSegments() const;
  /// The state as it was after solves[i]: the keyframes (of those still kept), odometry and
  /// loops of then, at that solve's poses (the tiles' images shared).
  SlamSnapshot AfterSolve(std::size_t i) const;
};

}  // namespace uwbsar::slam
