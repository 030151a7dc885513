#include "slam/session/landmark_join.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <utility>
#include <vector>

namespace uwbsar {

void CaptureLandmarks(const PoseGraph& graph, SessionData* d) {
  d->landmarks.clear();
  d->line_observations.clear();
  const std::vector<LineObservation> observations = graph.LineObservations();
  const std::vector<LineObservationReport> reports = graph.LineObservationReports();
  std::set<int> seen;
  for (std::size_t i = 0; i < observations.size(); ++i) {
    d->line_observations.push_back({observations[i], i < reports.size() && reports[i].rejected});
    seen.insert(observations[i].landmark_id);
  }
  for (const auto& [id, line] : graph.GetLandmarks()) {
    if (seen.count(id)) d->landmarks.push_back({id, line});
  }
}

std::map<int, std::vector<Point2>> LandmarkSightings(const SessionData& s,
                                                     const Pose2& T_map_session) {
  const std::map<int, Pose2> poses = s.Poses();
  std::map<int, std::vector<Point2>> out;
  for (const SessionLineObservation& o : s.line_observations) {
    const auto pose = poses.find(o.observation.node_id);
    if (o.rejected || pose == poses.end()) continue;
    const Line2& l = o.observation.line_node;
    const Point2& q = o.observation.reference_node;
    const double nx = std::cos(l.normal_rad), ny = std::sin(l.normal_rad);
    const double off = l.offset_m - (nx * q.x_m + ny * q.y_m);
    out[o.observation.landmark_id].push_back(T_map_session * pose->second *
                                             Point2{q.x_m + off * nx, q.y_m + off * ny});
  }
  return out;
}

namespace {

double Distance(const Line2& l, const Point2& p) { return std::abs(SignedDistance(l, p)); }

}  // namespace

int ReuseSavedWalls(const SessionData& a, const Pose2& T_mapA_mapB, const WallLineConfig& config,
                    double reach_m, SessionData* b) {
  const std::map<int, std::vector<Point2>> seen_a = LandmarkSightings(a, Pose2{});
  const std::map<int, std::vector<Point2>> seen_b = LandmarkSightings(*b, T_mapA_mapB);
  const double gate_rad = config.gate_angle_deg * M_PI / 180.0;
  std::map<int, std::pair<int, bool>> reused;  // b's landmark -> a's, turned over
  for (const SessionLandmark& lb : b->landmarks) {
    const auto points = seen_b.find(lb.id);
    if (points == seen_b.end()) continue;
    const Line2 line_b = LineToWorld(T_mapA_mapB, lb.line_map);
    double best = config.gate_offset_m;
    for (const SessionLandmark& la : a.landmarks) {
      const auto near = seen_a.find(la.id);
      if (near == seen_a.end()) continue;
      const Line2 facing = Facing(line_b, la.line_map);
      if (std::abs(NormalizeAngle(facing.normal_rad - la.line_map.normal_rad)) > gate_rad) continue;
      double worst = 0.0, closest = INFINITY;
      for (const Point2& p : points->second) {
        worst = std::max(worst, Distance(la.line_map, p));
        for (const Point2& q : near->second)
          closest = std::min(closest, std::hypot(p.x_m - q.x_m, p.y_m - q.y_m));
      }
      if (worst > best || closest > reach_m) continue;
      best = worst;
      reused[lb.id] = {la.id, facing.normal_rad != line_b.normal_rad};
    }
  }
  for (SessionLineObservation& o : b->line_observations) {
    const auto it = reused.find(o.observation.landmark_id);
    if (it == reused.end()) continue;
    o.observation.landmark_id = it->second.first;
    Line2& l = o.observation.line_node;
    if (it->second.second) l = {NormalizeAngle(l.normal_rad + M_PI), -l.offset_m};
  }
  b->landmarks.erase(std::remove_if(b->landmarks.begin(), b->landmarks.end(),
                                    [&](const SessionLandmark& l) { return reused.count(l.id); }),
                     b->landmarks.end());
  return static_cast<int>(reused.size());
}

}  // namespace uwbsar
