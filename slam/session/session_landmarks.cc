#include "slam/session/session_landmarks.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "slam/session/session_reader.h"
#include "slam/session/table_reader.h"

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

namespace {

/// Where each observation saw its wall, in the map frame (`T_map_session` places the session).
std::map<int, std::vector<Point2>> Sightings(const SessionData& s, const Pose2& T_map_session) {
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

double Distance(const Line2& l, const Point2& p) {
  return std::abs(std::cos(l.normal_rad) * p.x_m + std::sin(l.normal_rad) * p.y_m - l.offset_m);
}

}  // namespace

int ReuseSavedWalls(const SessionData& a, const Pose2& T_mapA_mapB, const WallLineConfig& config,
                    double reach_m, SessionData* b) {
  const std::map<int, std::vector<Point2>> seen_a = Sightings(a, Pose2{});
  const std::map<int, std::vector<Point2>> seen_b = Sightings(*b, T_mapA_mapB);
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

namespace uwbsar::session {

const char* const kLandmarkTablesSchema = R"sql(
CREATE TABLE landmarks (id INTEGER PRIMARY KEY, normal_rad REAL, offset_m REAL);
CREATE TABLE line_observations (
  idx INTEGER PRIMARY KEY, landmark_id INTEGER NOT NULL, keyframe_id INTEGER NOT NULL,
  normal_rad REAL, offset_m REAL, reference_x_m REAL, reference_y_m REAL, offset_std_m REAL,
  normal_std_rad REAL, rejected INTEGER NOT NULL);
)sql";

/// The landmarks and line_observations tables (walls as line landmarks).
void WriteLandmarkTables(SqliteDb& db, const SessionData& d) {
  SqliteStatement s(db, "INSERT INTO landmarks VALUES (?, ?, ?)");
  for (const SessionLandmark& l : d.landmarks) {
    s.Bind(1, l.id);
    s.Bind(2, l.line_map.normal_rad);
    s.Bind(3, l.line_map.offset_m);
    s.Run();
  }
  SqliteStatement o(db, "INSERT INTO line_observations VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?)");
  int idx = 0;
  for (const SessionLineObservation& so : d.line_observations) {
    const LineObservation& x = so.observation;
    o.Bind(1, idx++);
    o.Bind(2, x.landmark_id);
    o.Bind(3, x.node_id);
    o.Bind(4, x.line_node.normal_rad);
    o.Bind(5, x.line_node.offset_m);
    o.Bind(6, x.reference_node.x_m);
    o.Bind(7, x.reference_node.y_m);
    o.Bind(8, x.offset_std_m);
    o.Bind(9, x.normal_std_rad);
    o.Bind(10, so.rejected ? 1 : 0);
    o.Run();
  }
}

/// The landmarks and line_observations tables (format version 7).
void ReadLandmarkTables(SqliteDb& db, SessionData* d) {
  if (d->format_version < 7) return;
  constexpr double kMaxOffsetM = 1e7;
  std::set<int> landmarks;
  {
    TableReader t(db, "landmarks", {"id", "normal_rad", "offset_m"});
    while (t.Next()) {
      SessionLandmark l;
      l.id = t.Id("id");
      if (!landmarks.insert(l.id).second) t.Refuse("id", std::to_string(l.id) + " is already used");
      l.line_map.normal_rad = t.Real("normal_rad", -kMaxAngleRad, kMaxAngleRad);
      l.line_map.offset_m = t.Real("offset_m", -kMaxOffsetM, kMaxOffsetM);
      d->landmarks.push_back(l);
    }
  }
  std::sort(d->landmarks.begin(), d->landmarks.end(),
            [](const SessionLandmark& a, const SessionLandmark& b) { return a.id < b.id; });
  std::set<int> keyframes;
  for (const SessionKeyframe& k : d->keyframes) keyframes.insert(k.id);
  TableReader t(db, "line_observations",
                {"idx", "landmark_id", "keyframe_id", "normal_rad", "offset_m", "reference_x_m",
                 "reference_y_m", "offset_std_m", "normal_std_rad", "rejected"});
  std::vector<std::pair<std::int64_t, SessionLineObservation>> observations;
  while (t.Next()) {
    SessionLineObservation so;
    LineObservation& o = so.observation;
    const std::int64_t idx = t.Integer("idx", 0, INT_MAX);
    o.landmark_id = t.Id("landmark_id");
    if (!landmarks.count(o.landmark_id))
      t.Refuse("landmark_id", std::to_string(o.landmark_id) + " is not a landmark");
    o.node_id = KeyframeRef(t, "keyframe_id", keyframes);
    o.line_node.normal_rad = t.Real("normal_rad", -kMaxAngleRad, kMaxAngleRad);
    o.line_node.offset_m = t.Real("offset_m", -kMaxOffsetM, kMaxOffsetM);
    o.reference_node.x_m = t.Real("reference_x_m", -kMaxOffsetM, kMaxOffsetM);
    o.reference_node.y_m = t.Real("reference_y_m", -kMaxOffsetM, kMaxOffsetM);
    o.offset_std_m = t.Real("offset_std_m", 0.0, kMaxOffsetM);
    o.normal_std_rad = t.Real("normal_std_rad", 0.0, kMaxAngleRad);
    if (!(o.offset_std_m > 0.0)) t.Refuse("offset_std_m", "must be > 0");
    if (!(o.normal_std_rad > 0.0)) t.Refuse("normal_std_rad", "must be > 0");
    so.rejected = t.Flag("rejected");
    observations.emplace_back(idx, so);
  }
  std::stable_sort(observations.begin(), observations.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  for (const auto& [idx, so] : observations) d->line_observations.push_back(so);
}

}  // namespace uwbsar::session
