// The loops table as session format versions 1 to 3 laid it out (good-match counts in the
// akaze_good and orb_good columns), made from a version 4 file's loops and loop_matches
// tables: the tests that open older versions rewrite a freshly written file with it.
#pragma once

namespace uwbsar::testing {

/// SQL turning a version 4 file's loop tables into the version 3 layout (the format_version
/// in meta is left to the caller).
inline constexpr const char* kLoopsToVersion3Sql = R"sql(
CREATE TABLE loops_v3 (
  query_id INTEGER NOT NULL, match_id INTEGER NOT NULL, validated INTEGER NOT NULL,
  accepted INTEGER NOT NULL, x_m REAL, y_m REAL, yaw_rad REAL, chi2 REAL,
  akaze_good INTEGER, orb_good INTEGER, reason TEXT);
INSERT INTO loops_v3 SELECT query_id, match_id, validated, accepted, x_m, y_m, yaw_rad, chi2,
  (SELECT good FROM loop_matches WHERE loop_idx = idx AND detector = 'AKAZE'),
  (SELECT good FROM loop_matches WHERE loop_idx = idx AND detector = 'ORB'), reason
  FROM loops ORDER BY idx;
DROP TABLE loops;
DROP TABLE loop_matches;
ALTER TABLE loops_v3 RENAME TO loops;
)sql";

}  // namespace uwbsar::testing
