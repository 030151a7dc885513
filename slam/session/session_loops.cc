#include "slam/session/session_loops.h"

#include <algorithm>
#include <climits>
#include <limits>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "slam/session/session_reader.h"
#include "slam/session/table_reader.h"

namespace uwbsar::session {

const char* const kLoopTablesSchema = R"sql(
CREATE TABLE loops (
  idx INTEGER PRIMARY KEY, query_id INTEGER NOT NULL, match_id INTEGER NOT NULL,
  validated INTEGER NOT NULL, accepted INTEGER NOT NULL, x_m REAL, y_m REAL, yaw_rad REAL,
  chi2 REAL, reason TEXT);
CREATE TABLE loop_matches (
  loop_idx INTEGER NOT NULL, detector TEXT NOT NULL, good INTEGER NOT NULL,
  PRIMARY KEY (loop_idx, detector));
)sql";

void WriteLoopTables(SqliteDb& db, const SessionData& d) {
  SqliteStatement s(db, "INSERT INTO loops VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?)");
  SqliteStatement m(db, "INSERT INTO loop_matches VALUES (?, ?, ?)");
  int idx = 0;
  for (const SessionLoop& l : d.loops) {
    s.Bind(1, idx);
    s.Bind(2, l.query_id);
    s.Bind(3, l.match_id);
    s.Bind(4, l.validated ? 1 : 0);
    s.Bind(5, l.accepted ? 1 : 0);
    s.Bind(6, l.T_ij.x_m);
    s.Bind(7, l.T_ij.y_m);
    s.Bind(8, l.T_ij.yaw_rad);
    s.Bind(9, l.chi2);
    s.Bind(10, l.reason);
    s.Run();
    for (const auto& [kind, good] : l.good_matches) {
      m.Bind(1, idx);
      m.Bind(2, std::string(DetectorName(kind)));
      m.Bind(3, good);
      m.Run();
    }
    ++idx;
  }
}

namespace {

/// The loops table without its counts; `idx` of each row (versions 1 to 3: the row's place).
std::vector<std::pair<int, SessionLoop>> ReadLoopRows(SqliteDb& db, const SessionData& d) {
  const bool v4 = d.format_version >= 4;
  std::vector<std::string> required = {"query_id", "match_id", "validated", "accepted", "x_m",
                                       "y_m",      "yaw_rad",  "chi2",      "reason"};
  if (v4) {
    required.push_back("idx");
  } else {
    required.push_back("akaze_good");
    required.push_back("orb_good");
  }
  TableReader t(db, "loops", required);
  std::set<int> keyframes;
  for (const SessionKeyframe& k : d.keyframes) keyframes.insert(k.id);
  std::vector<std::pair<int, SessionLoop>> rows;
  std::set<int> seen;
  while (t.Next()) {
    SessionLoop l;
    const int idx = v4 ? t.Id("idx") : static_cast<int>(rows.size());
    if (!seen.insert(idx).second) t.Refuse("idx", std::to_string(idx) + " appears twice");
    l.query_id = KeyframeRef(t, "query_id", keyframes);
    l.match_id = KeyframeRef(t, "match_id", keyframes);
    if (l.match_id == l.query_id)
      t.Refuse("match_id", std::to_string(l.match_id) + " equals query_id");
    l.validated = t.Flag("validated");
    l.accepted = t.Flag("accepted");
    if (l.accepted && !l.validated) t.Refuse("accepted", "is 1 for a loop not validated");
    l.T_ij.x_m = t.Real("x_m", -kMaxCoordinateM, kMaxCoordinateM);
    l.T_ij.y_m = t.Real("y_m", -kMaxCoordinateM, kMaxCoordinateM);
    l.T_ij.yaw_rad = t.Real("yaw_rad", -kMaxAngleRad, kMaxAngleRad);
    // NULL (a NaN chi2: never solved) reads as NaN; else finite and >= 0.
    l.chi2 = t.RealOrNaN("chi2", 0.0, std::numeric_limits<double>::max());
    if (!v4) {
      // The paper's pair, which is all that versions 1 to 3 could record.
      l.good_matches[DetectorKind::kAkaze] = static_cast<int>(t.Integer("akaze_good", 0, INT_MAX));
      l.good_matches[DetectorKind::kOrb] = static_cast<int>(t.Integer("orb_good", 0, INT_MAX));
    }
    l.reason = t.Text("reason", /*required=*/false);
    rows.emplace_back(idx, l);
  }
  return rows;
}

}  // namespace

void ReadLoopTables(SqliteDb& db, SessionData* d) {
  std::vector<std::pair<int, SessionLoop>> rows = ReadLoopRows(db, *d);
  if (d->format_version >= 4) {
    std::map<int, SessionLoop*> by_idx;
    for (auto& [idx, l] : rows) by_idx[idx] = &l;
    TableReader t(db, "loop_matches", {"loop_idx", "detector", "good"});
    while (t.Next()) {
      const int idx = t.Id("loop_idx");
      const auto it = by_idx.find(idx);
      if (it == by_idx.end()) t.Refuse("loop_idx", std::to_string(idx) + " is not a loop");
      const std::string name = t.Text("detector");
      DetectorKind kind = DetectorKind::kAkaze;
      if (!ParseDetector(name, &kind))
        t.Refuse("detector", "'" + name.substr(0, 40) + "' is not a detector");
      if (!it->second->good_matches.emplace(kind, static_cast<int>(t.Integer("good", 0, INT_MAX)))
               .second) {
        t.Refuse("detector", name + " of loop " + std::to_string(idx) + " appears twice");
      }
    }
  }
  std::stable_sort(rows.begin(), rows.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  for (auto& [idx, l] : rows) d->loops.push_back(std::move(l));
}

}  // namespace uwbsar::session
