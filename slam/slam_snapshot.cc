#include "slam/slam_snapshot.h"

#include <algorithm>
#include <map>

namespace uwbsar::slam {

const MatchResult& LoopRecord::Match(DetectorKind kind) const {
  static const MatchResult kNotMatched;
  return Of(matches, kind, kNotMatched);
}

std::vector<DetectorKind> SlamSnapshot::LoopDetectors() const {
  return config != nullptr ? config->place_recognition.validation.detectors
                           : LoopValidationConfig().detectors;
}

std::map<int, Pose2> RetiredPoses(const std::vector<RetiredKeyframe>& retired,
                                  const std::map<int, Pose2>& poses) {
  std::map<int, Pose2> out;
  // Later retirements first: a hub retired after the keyframe folded into it is resolved
  // before that keyframe is.
  for (auto it = retired.rbegin(); it != retired.rend(); ++it) {
    if (it->hub_id < 0) {
      out[it->id] = it->T_hub_anchor;
      continue;
    }
    auto kept = poses.find(it->hub_id);
    if (kept != poses.end()) {
      out[it->id] = kept->second * it->T_hub_anchor;
      continue;
    }
    auto folded = out.find(it->hub_id);
    if (folded != out.end()) out[it->id] = folded->second * it->T_hub_anchor;
  }
  return out;
}

std::vector<TrajectoryAnchor> MergeAnchors(std::vector<TrajectoryAnchor> kept,
                                           const std::vector<TrajectoryAnchor>& retired) {
  kept.insert(kept.end(), retired.begin(), retired.end());
  std::stable_sort(
      kept.begin(), kept.end(),
      [](const TrajectoryAnchor& a, const TrajectoryAnchor& b) { return a.stamp_ns < b.stamp_ns; });
  return kept;
}

Pose2 CorrectionAt(const std::vector<TrajectoryAnchor>& anchors, TimestampNs stamp_ns) {
  return InterpolatedCorrection(
      anchors.size(), [&](std::size_t i) { return anchors[i].stamp_ns; },
      [&](std::size_t i) -> const Pose2& { return anchors[i].T_odom_anchor; },
      [&](std::size_t i) { return anchors[i].T_world_anchor; }, stamp_ns);
}

std::vector<TrajectoryAnchor> SlamSnapshot::Anchors() const {
  std::vector<TrajectoryAnchor> kept;
  kept.reserve(tiles.size());
  for (const TileSnapshot& t : tiles) {
    auto p = poses.find(t.id);
    if (p != poses.end()) kept.push_back({t.id, t.stamp_ns, t.T_world_anchor, p->second});
  }
  return MergeAnchors(std::move(kept), retired);
}

Pose2 SlamSnapshot::CorrectionAt(TimestampNs stamp_ns) const {
  return uwbsar::slam::CorrectionAt(Anchors(), stamp_ns);
}

std::vector<std::pair<TimestampNs, Pose2>> SlamSnapshot::CorrectedTrajectory() const {
  const std::vector<TrajectoryAnchor> anchors = Anchors();
  std::vector<std::pair<TimestampNs, Pose2>> out;
  out.reserve(odometry.size());
  for (const OdometryEntry& e : odometry) {
    out.push_back({e.stamp_ns, uwbsar::slam::CorrectionAt(anchors, e.stamp_ns) * e.T_world_robot});
  }
  return out;
}

std::vector<std::pair<Point2, Point2>> SlamSnapshot::AcceptedLoopSegments() const {
  std::vector<std::pair<Point2, Point2>> out;
  for (const LoopRecord& l : loops) {
    const auto a = poses.find(l.match_id), b = poses.find(l.query_id);
    if (!l.accepted() || a == poses.end() || b == poses.end()) continue;
    out.push_back({{a->second.x_m, a->second.y_m}, {b->second.x_m, b->second.y_m}});
  }
  return out;
}

SlamSnapshot SlamSnapshot::AfterSolve(std::size_t i) const {
  const SolveRecord& solve = solves.at(i);
  SlamSnapshot s;
  s.config = config;
  s.sensors = sensors;
  std::map<int, Pose2> then;
  for (std::size_t k = 0; k < solve.ids.size() && k < solve.poses.size(); ++k)
    then[solve.ids[k]] = solve.poses[k];
  for (const TileSnapshot& t : tiles) {
    auto p = then.find(t.id);
    if (p == then.end()) continue;  // came later, or retired since (its tile is gone)
    s.tiles.push_back(t);
    s.poses[t.id] = p->second;
  }
  s.odometry.assign(odometry.begin(), odometry.begin() + static_cast<std::ptrdiff_t>(std::min(
                                                             solve.num_odometry, odometry.size())));
  s.loops.assign(loops.begin(), loops.begin() + static_cast<std::ptrdiff_t>(
                                                    std::min(solve.num_loops, loops.size())));
  return s;
}

}  // namespace uwbsar::slam
