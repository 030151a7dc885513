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
