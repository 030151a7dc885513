#include "slam/slam_snapshot.h"

#include <algorithm>

namespace uwbsar::slam {

const MatchResult& LoopRecord::Match(DetectorKind kind) const {
  static const MatchResult kNotMatched;
  return Of(matches, kind, kNotMatched);
}

std::vector<DetectorKind> SlamSnapshot::LoopDetectors() const {
  return config != nullptr ? config->place_recognition.validation.detectors
                           : LoopValidationConfig().detectors;
}

Pose2 SlamSnapshot::CorrectionAt(TimestampNs stamp_ns) const {
  return InterpolatedCorrection(
      tiles.size(), [&](std::size_t i) { return tiles[i].stamp_ns; },
      [&](std::size_t i) -> const Pose2& { return tiles[i].T_world_anchor; },
      [&](std::size_t i) { return poses.at(tiles[i].id); }, stamp_ns);
}

std::vector<std::pair<TimestampNs, Pose2>> SlamSnapshot::CorrectedTrajectory() const {
  std::vector<std::pair<TimestampNs, Pose2>> out;
  out.reserve(odometry.size());
  for (const OdometryEntry& e : odometry) {
    out.push_back({e.stamp_ns, CorrectionAt(e.stamp_ns) * e.T_world_robot});
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
  const std::size_t n = std::min(solve.num_keyframes, tiles.size());
  s.tiles.assign(tiles.begin(), tiles.begin() + static_cast<std::ptrdiff_t>(n));
  for (std::size_t k = 0; k < n && k < solve.poses.size(); ++k) {
    s.poses[tiles[k].id] = solve.poses[k];
  }
  s.odometry.assign(odometry.begin(), odometry.begin() + static_cast<std::ptrdiff_t>(std::min(
                                                             solve.num_odometry, odometry.size())));
  s.loops.assign(loops.begin(), loops.begin() + static_cast<std::ptrdiff_t>(
                                                    std::min(solve.num_loops, loops.size())));
  return s;
}

}  // namespace uwbsar::slam
