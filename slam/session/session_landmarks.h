// The wall landmarks of a session file (format version 7; place_recognition.wall_profiles.
// landmarks): the landmarks table (each wall's line in the map frame) and the
// line_observations table (each keyframe's measurement of one, backend/line_landmark.h).
// Sessions of versions 1 to 6 have none.
#pragma once

#include "frontend/wall_line_config.h"
#include "slam/session/session_data.h"
#include "slam/session/sqlite_db.h"

namespace uwbsar {

/// d's landmarks and line observations as `graph` holds them after its last solve: the
/// observations of its nodes, and the landmarks that some observation still sees (a wall whose
/// keyframes were all retired leaves with them).
void CaptureLandmarks(const PoseGraph& graph, SessionData* d);

/// A new run joining a saved map sees the map's walls again: each of b's landmarks that lies on
/// one of a's (b placed in a's frame by T_mapA_mapB; within config.gate_angle_deg, every one of
/// its sightings within config.gate_offset_m of a's line, and some sighting within
/// `reach_m` of one of a's) is that landmark: its observations are re-pointed to a's landmark
/// (their lines turned to face it) and it leaves b. Returns how many were reused. b's ids must
/// not collide with a's (Renumbered).
int ReuseSavedWalls(const SessionData& a, const Pose2& T_mapA_mapB, const WallLineConfig& config,
                    double reach_m, SessionData* b);

}  // namespace uwbsar

namespace uwbsar::session {

/// The CREATE TABLE statements of the landmarks and line_observations tables.
extern const char* const kLandmarkTablesSchema;

/// Writes d.landmarks and d.line_observations into the (empty) tables.
void WriteLandmarkTables(SqliteDb& db, const SessionData& d);

/// Reads both tables (from format version 7) into d; d's keyframes and format_version are
/// already read. Throws InputError naming the file, table, row and column.
void ReadLandmarkTables(SqliteDb& db, SessionData* d);

}  // namespace uwbsar::session
