#include "slam/map_walls.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "slam/session/landmark_join.h"

namespace uwbsar::slam {

MapWalls::MapWalls(const SessionData& map, const WallLineConfig& gates, double reach_m)
    : gate_angle_rad_(gates.gate_angle_deg * M_PI / 180.0),
      gate_offset_m_(gates.gate_offset_m),
      reach_m_(reach_m),
      sightings_(LandmarkSightings(map, Pose2{})) {
  for (const SessionLandmark& l : map.landmarks) {
    if (sightings_.count(l.id)) lines_[l.id] = l.line_map;  // a wall nobody saw cannot be met
  }
}

std::vector<LineObservation> MapWalls::Observe(const std::vector<SeenLine>& walls,
                                               const Pose2& T_map_anchor, int node_id) const {
  std::map<int, std::pair<double, LineObservation>> nearest;  // by landmark
  for (const SeenLine& seen : walls) {
    const Line2 seen_map = LineToWorld(T_map_anchor, seen.line_anchor);
    const Point2 q = T_map_anchor * seen.reference_anchor;
    for (const auto& [id, line] : lines_) {
      const double turn_rad = NormalizeAngle(Facing(seen_map, line).normal_rad - line.normal_rad);
      if (std::abs(turn_rad) > gate_angle_rad_) continue;
      const double off_m = std::abs(SignedDistance(line, q));
      if (off_m > gate_offset_m_) continue;
      double closest_m = INFINITY;
      for (const Point2& p : sightings_.at(id)) {
        closest_m = std::min(closest_m, std::hypot(p.x_m - q.x_m, p.y_m - q.y_m));
      }
      if (closest_m > reach_m_) continue;
      const auto it = nearest.find(id);
      if (it != nearest.end() && it->second.first <= off_m) continue;
      LineObservation o;
      o.landmark_id = id;
      o.node_id = node_id;
      o.line_node = Facing(seen.line_anchor, LineToFrame(T_map_anchor, line));
      o.reference_node = seen.reference_anchor;
      o.offset_std_m = seen.offset_std_m;
      o.normal_std_rad = seen.normal_std_rad;
      nearest[id] = {off_m, o};
    }
  }
  std::vector<LineObservation> out;
  for (const auto& [id, best] : nearest) out.push_back(best.second);
  return out;
}

}  // namespace uwbsar::slam
