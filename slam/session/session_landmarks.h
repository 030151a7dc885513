// The wall landmarks of a session file (format version 7; place_recognition.wall_profiles.
// landmarks): the landmarks table (each wall's line in the map frame) and the
// line_observations table (each keyframe's measurement of one, backend/line_landmark.h).
// Sessions of versions 1 to 6 have none.
#pragma once

#include "slam/session/session_data.h"
#include "slam/session/sqlite_db.h"

namespace uwbsar::session {

/// The CREATE TABLE statements of the landmarks and line_observations tables.
extern const char* const kLandmarkTablesSchema;

/// Writes d.landmarks and d.line_observations into the (empty) tables.
void WriteLandmarkTables(SqliteDb& db, const SessionData& d);

/// Reads both tables (from format version 7) into d; d's keyframes and format_version are
/// already read. Throws InputError naming the file, table, row and column.
void ReadLandmarkTables(SqliteDb& db, SessionData* d);

}  // namespace uwbsar::session
