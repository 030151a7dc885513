// The loop records of a session file: the loops table and, from format version 4, the
// loop_matches table with each loop's good-match count per detector (the detectors of
// place_recognition.validation.detectors when it was made). Versions 1 to 3 kept the counts
// in the loops table's akaze_good and orb_good columns: they read as AKAZE and ORB entries.
#pragma once

#include "slam/session/session_data.h"
#include "slam/session/sqlite_db.h"

namespace uwbsar::session {

/// The CREATE TABLE statements of the loops and loop_matches tables (format version 4).
extern const char* const kLoopTablesSchema;

/// Writes d.loops into the (empty) loops and loop_matches tables.
void WriteLoopTables(SqliteDb& db, const SessionData& d);

/// Reads the loops (and, from version 4, loop_matches) table into d->loops; d's keyframes and
/// format_version are already read. Throws InputError naming the file, table, row and column.
void ReadLoopTables(SqliteDb& db, SessionData* d);

}  // namespace uwbsar::session
