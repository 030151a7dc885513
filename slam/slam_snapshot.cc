#include "slam/slam_snapshot.h"

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

}  // namespace uwbsar::slam
