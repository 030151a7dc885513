// The session file `session.uwbsar` (docs/formats.md, "Session file"): an sqlite3 database that
// opens without uwbsar (`sqlite3 session.uwbsar .tables`). Tables: meta (format, version,
// config YAML, config fingerprint), trajectories, keyframes (poses, tile, feature grid),
// features (AKAZE/ORB keypoints and descriptors), edges (pose graph with information),
// loops and odometry. Tiles and descriptors are stored losslessly (blob_codec.h).
#pragma once

#include <string>

#include "slam/config/system_config.h"
#include "slam/session/session_data.h"

namespace uwbsar {

/// The file name `uwbsar map` writes into its output folder.
constexpr const char* kSessionFileName = "session.uwbsar";

/// Writes `data` to `path` atomically: into `path`.tmp-<pid> first, renamed at the end.
/// Throws std::runtime_error when the folder cannot be written, e.g. "<path>: cannot write: no
/// space left on device" on a full disk (an I/O failure, exit 1; the temporary file removed).
void WriteSession(const std::string& path, const SessionData& data);

/// A folder holding session.uwbsar, or the file itself.
std::string ResolveSessionPath(const std::string& dir_or_file);

/// Reads a session (format versions 1 to kSessionFormatVersion). Throws InputError (one line
/// naming the file) for a missing, foreign or damaged file and for another format version, for
/// a missing column or a value out of range ("<file>: <table> row <n>: <column> <what is
/// wrong>", session_reader.h), and for a blob declaring more than limits.max_tile_pixels
/// (`config`'s limits, else the defaults; checked before decoding); with `config`, also when
/// its compatibility-relevant settings (config_fingerprint.h) differ, naming the first key.
SessionData ReadSession(const std::string& path, const SystemConfig* config = nullptr);

}  // namespace uwbsar
