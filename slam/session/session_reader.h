// The tables of a session file read into SessionData (session_file.cc reads the meta table
// and calls this): every table by column name, every value range-checked (table_reader.h),
// every reference resolved (keyframes and odometry to trajectories, features, edges and loops
// to keyframes), and the sizes blobs declare checked against `limits` before allocation.
#pragma once

#include <set>
#include <string>

#include "core/limits_config.h"
#include "slam/session/session_data.h"
#include "slam/session/sqlite_db.h"
#include "slam/session/table_reader.h"

namespace uwbsar::session {

/// Sane bounds on the values of a session (beyond them a value is damage, not data).
/// |x|, |y| of any pose or grid origin: what uwbsar reads from any file (core/pose2.h).
constexpr double kMaxCoordinateM = kMaxWorldCoordinateM;
constexpr double kMaxAngleRad = 1e6;  ///< |yaw| (yaws need not be normalised)
constexpr double kMaxPathM = 1e9;     ///< |path| of odometry and keyframes
constexpr double kMinResolutionM = 1e-4;
constexpr double kMaxResolutionM = 10.0;

/// Reads the trajectories, keyframes (with features), edges, loops and odometry of `db`, whose
/// d->format_version is already set, into `d`. Throws InputError, one line naming the file.
void ReadSessionTables(SqliteDb& db, const LimitsConfig& limits, SessionData* d);

/// The value of a keyframe column of `t`: an id of `keyframes` (else refused, naming the row).
int KeyframeRef(const TableReader& t, const std::string& column, const std::set<int>& keyframes);

}  // namespace uwbsar::session
