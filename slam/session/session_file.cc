#include "slam/session/session_file.h"

#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <filesystem>

#include "core/bounded_file.h"
#include "core/errors.h"
#include "slam/config/config_fingerprint.h"
#include "slam/session/blob_checksum.h"
#include "slam/session/blob_codec.h"
#include "slam/session/session_landmarks.h"
#include "slam/session/session_loops.h"
#include "slam/session/session_reader.h"
#include "slam/session/sqlite_db.h"

namespace uwbsar {
namespace fs = std::filesystem;
using session::SqliteDb;
using session::SqliteStatement;

namespace {

constexpr const char* kFormatName = "uwbsar-session";
constexpr int kZstdLevel = 3;

constexpr const char* kSchema = R"sql(
CREATE TABLE meta (key TEXT PRIMARY KEY, value TEXT NOT NULL);
CREATE TABLE trajectories (id INTEGER PRIMARY KEY, input TEXT NOT NULL, fingerprint TEXT);
CREATE TABLE keyframes (
  id INTEGER PRIMARY KEY, trajectory INTEGER NOT NULL, stamp_ns INTEGER NOT NULL,
  odom_x_m REAL, odom_y_m REAL, odom_yaw_rad REAL,
  robot_x_m REAL, robot_y_m REAL, robot_yaw_rad REAL,
  x_m REAL, y_m REAL, yaw_rad REAL, fixed INTEGER NOT NULL,
  path_begin_m REAL, path_end_m REAL,
  tile_x0_m REAL, tile_y0_m REAL, tile_resolution_m REAL, tile BLOB NOT NULL,
  feature_x0_m REAL, feature_y0_m REAL, feature_resolution_m REAL,
  feature_rows INTEGER, feature_cols INTEGER, centre_x_m REAL, centre_y_m REAL,
  tile_xxh3 INTEGER NOT NULL);
CREATE TABLE features (
  keyframe_id INTEGER NOT NULL, detector TEXT NOT NULL, norm_type INTEGER NOT NULL,
  keypoints BLOB NOT NULL, descriptors BLOB NOT NULL, keypoints_xxh3 INTEGER NOT NULL,
  descriptors_xxh3 INTEGER NOT NULL, PRIMARY KEY (keyframe_id, detector));
CREATE TABLE edges (
  idx INTEGER PRIMARY KEY, from_id INTEGER NOT NULL, to_id INTEGER NOT NULL, kind TEXT NOT NULL,
  x_m REAL, y_m REAL, yaw_rad REAL, information BLOB NOT NULL, rejected INTEGER NOT NULL,
  trajectory INTEGER NOT NULL, path_m REAL, turn_rad REAL, information_xxh3 INTEGER NOT NULL);
CREATE TABLE odometry (
  trajectory INTEGER NOT NULL, stamp_ns INTEGER NOT NULL, x_m REAL, y_m REAL, yaw_rad REAL,
  path_m REAL);
CREATE TABLE anchors (
  id INTEGER PRIMARY KEY, trajectory INTEGER NOT NULL, stamp_ns INTEGER NOT NULL,
  odom_x_m REAL, odom_y_m REAL, odom_yaw_rad REAL, hub_id INTEGER NOT NULL,
  x_m REAL, y_m REAL, yaw_rad REAL);
)sql";

std::vector<unsigned char> InformationBlob(const Eigen::Matrix3d& m) {
  std::vector<unsigned char> out(9 * sizeof(double));
  double v[9];
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) v[r * 3 + c] = m(r, c);
  std::memcpy(out.data(), v, sizeof(v));
  return out;
}

/// Binds `blob` at `index` and its checksum (blob_checksum.h) at `checksum_index`.
void BindChecksummed(SqliteStatement& s, int index, int checksum_index,
                     const std::vector<unsigned char>& blob) {
  s.BindBlob(index, blob);
  s.Bind(checksum_index, session::BlobChecksum(blob));
}

void WriteFeatures(SqliteStatement& s, int id, const char* name, const FeatureSet& f) {
  s.Bind(1, id);
  s.Bind(2, std::string(name));
  s.Bind(3, f.norm_type);
  BindChecksummed(s, 4, 6, session::EncodeKeypoints(f.keypoints, kZstdLevel));
  BindChecksummed(s, 5, 7, session::EncodeMat(f.descriptors, kZstdLevel));
  s.Run();
}

/// The meta table: format, version and the configuration.
void WriteMeta(SqliteDb& db, const SessionData& d) {
  SqliteStatement s(db, "INSERT INTO meta VALUES (?, ?)");
  for (const auto& [k, v] : std::vector<std::pair<std::string, std::string>>{
           {"format", kFormatName},
           {"format_version", std::to_string(kSessionFormatVersion)},
           {"config_yaml", d.config_yaml},
           {"config_fingerprint", d.fingerprint}}) {
    s.Bind(1, k);
    s.Bind(2, v);
    s.Run();
  }
}

/// The trajectories table: one row per run (a run of unknown identity as kUnknownRunFingerprint).
void WriteTrajectories(SqliteDb& db, const SessionData& d) {
  SqliteStatement s(db, "INSERT INTO trajectories (id, input, fingerprint) VALUES (?, ?, ?)");
  for (const SessionTrajectory& t : d.trajectories) {
    s.Bind(1, t.id);
    s.Bind(2, t.input);
    s.Bind(3, t.fingerprint.empty() ? std::string(kUnknownRunFingerprint) : t.fingerprint);
    s.Run();
  }
}

/// The keyframes table and each keyframe's rows of the features table, one per detector.
void WriteKeyframes(SqliteDb& db, const SessionData& d, bool lossless_tiles) {
  SqliteStatement s(db,
                    "INSERT INTO keyframes VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, "
                    "?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)");
  SqliteStatement f(db, "INSERT INTO features VALUES (?, ?, ?, ?, ?, ?, ?)");
  for (const SessionKeyframe& k : d.keyframes) {
    int i = 1;
    s.Bind(i++, k.id);
    s.Bind(i++, k.trajectory);
    s.Bind(i++, static_cast<std::int64_t>(k.stamp_ns));
    for (const Pose2* p : {&k.T_odom_anchor, &k.T_odom_robot, &k.T_map_anchor}) {
      s.Bind(i++, p->x_m);
      s.Bind(i++, p->y_m);
      s.Bind(i++, p->yaw_rad);
    }
    s.Bind(i++, k.fixed ? 1 : 0);
    s.Bind(i++, k.path_begin_m);
    s.Bind(i++, k.path_end_m);
    s.Bind(i++, k.detected_grid.x0_m);
    s.Bind(i++, k.detected_grid.y0_m);
    s.Bind(i++, k.detected_grid.resolution_m);
    const int tile_index = i++;  // its checksum goes last (tile_xxh3)
    const ImageGrid& g = k.features.grid;
    s.Bind(i++, g.x0_m);
    s.Bind(i++, g.y0_m);
    s.Bind(i++, g.resolution_m);
    s.Bind(i++, g.rows);
    s.Bind(i++, g.cols);
    s.Bind(i++, k.features.centre_anchor.x_m);
    s.Bind(i++, k.features.centre_anchor.y_m);
    BindChecksummed(s, tile_index, i++,
                    session::EncodeTile(k.detected.Load(), lossless_tiles, kZstdLevel));
    s.Run();
    for (const auto& [kind, features] : k.features.by_detector)
      WriteFeatures(f, k.id, DetectorName(kind), features);
  }
}

/// The edges table, in the pose graph's order (idx).
void WriteEdges(SqliteDb& db, const SessionData& d) {
  SqliteStatement s(db, "INSERT INTO edges VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)");
  int idx = 0;
  for (const SessionEdge& e : d.edges) {
    s.Bind(1, idx++);
    s.Bind(2, e.edge.from_id);
    s.Bind(3, e.edge.to_id);
    s.Bind(4, std::string(EdgeKindName(e.edge.kind)));
    s.Bind(5, e.edge.T_from_to.x_m);
    s.Bind(6, e.edge.T_from_to.y_m);
    s.Bind(7, e.edge.T_from_to.yaw_rad);
    BindChecksummed(s, 8, 13, InformationBlob(e.edge.information));
    s.Bind(9, e.rejected ? 1 : 0);
    s.Bind(10, e.edge.trajectory);
    s.Bind(11, e.edge.path_m);
    s.Bind(12, e.edge.turn_rad);  // NaN (the yaw of T) is stored as NULL
    s.Run();
  }
}

/// The odometry table.
void WriteOdometry(SqliteDb& db, const SessionData& d) {
  SqliteStatement s(db, "INSERT INTO odometry VALUES (?, ?, ?, ?, ?, ?)");
  for (const SessionOdometry& o : d.odometry) {
    s.Bind(1, o.trajectory);
    s.Bind(2, static_cast<std::int64_t>(o.stamp_ns));
    s.Bind(3, o.T_odom_robot.x_m);
    s.Bind(4, o.T_odom_robot.y_m);
    s.Bind(5, o.T_odom_robot.yaw_rad);
    s.Bind(6, o.path_m);
    s.Run();
  }
}

/// The anchors table (keyframes the map retired).
void WriteAnchors(SqliteDb& db, const SessionData& d) {
  SqliteStatement s(db, "INSERT INTO anchors VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?)");
  for (const SessionAnchor& a : d.anchors) {
    s.Bind(1, a.id);
    s.Bind(2, a.trajectory);
    s.Bind(3, static_cast<std::int64_t>(a.stamp_ns));
    s.Bind(4, a.T_odom_anchor.x_m);
    s.Bind(5, a.T_odom_anchor.y_m);
    s.Bind(6, a.T_odom_anchor.yaw_rad);
    s.Bind(7, a.hub_id);
    s.Bind(8, a.T_hub_anchor.x_m);
    s.Bind(9, a.T_hub_anchor.y_m);
    s.Bind(10, a.T_hub_anchor.yaw_rad);
    s.Run();
  }
}

void WriteAll(SqliteDb& db, const SessionData& d, bool lossless_tiles) {
  db.Exec("PRAGMA journal_mode = OFF; PRAGMA synchronous = OFF;");
  db.Exec(kSchema);
  db.Exec(session::kLoopTablesSchema);
  db.Exec(session::kLandmarkTablesSchema);
  db.Exec("BEGIN");
  WriteMeta(db, d);
  WriteTrajectories(db, d);
  WriteKeyframes(db, d, lossless_tiles);
  WriteEdges(db, d);
  session::WriteLoopTables(db, d);
  WriteOdometry(db, d);
  WriteAnchors(db, d);
  session::WriteLandmarkTables(db, d);
  db.Exec("COMMIT");
}

std::string Meta(SqliteDb& db, const std::string& key) {
  SqliteStatement s(db, "SELECT value FROM meta WHERE key = ?");
  s.Bind(1, key);
  if (!s.Step()) throw InputError(db.path() + ": not a uwbsar session (no meta." + key + ")");
  return s.Text(0);
}

}  // namespace

void WriteSession(const std::string& path, const SessionData& data, bool lossless_tiles) {
  const std::string tmp = path + ".tmp-" + std::to_string(::getpid());
  std::error_code ec;
  fs::remove(tmp, ec);
  try {
    SqliteDb db(tmp, /*create=*/true, /*name_in_errors=*/path);
    WriteAll(db, data, lossless_tiles);
  } catch (...) {
    fs::remove(tmp, ec);
    throw;
  }
  fs::rename(tmp, path, ec);
  if (ec) {
    fs::remove(tmp, ec);
    throw std::runtime_error(path + ": cannot write the session: " + ec.message());
  }
}

std::string ResolveSessionPath(const std::string& dir_or_file) {
  std::error_code ec;
  if (fs::is_directory(dir_or_file, ec)) return (fs::path(dir_or_file) / kSessionFileName).string();
  return dir_or_file;
}

SessionData ReadSession(const std::string& path, const SystemConfig* config) {
  std::error_code ec;
  if (!fs::exists(path, ec)) throw InputError(path + ": no session file there");
  CheckInputFile(path, "session");  // a folder, FIFO or device, named
  SqliteDb db(path, /*create=*/false);
  {
    // A foreign sqlite file (or not sqlite at all) fails here, with a clear line.
    try {
      if (!db.HasTable("meta")) throw InputError(path + ": not a uwbsar session (no meta table)");
    } catch (const InputError& e) {
      const std::string m = e.what();
      throw InputError(m.find("not a uwbsar session") != std::string::npos
                           ? m
                           : path + ": not a uwbsar session (" + m.substr(path.size() + 2) + ")");
    }
  }
  SessionData d;
  if (Meta(db, "format") != kFormatName) throw InputError(path + ": not a uwbsar session");
  const std::string version = Meta(db, "format_version");
  // Version 1 lacks the edges' calibration columns (its odometry edges are then solved
  // uncalibrated, as they were), versions 1 and 2 the trajectories' fingerprints (""), versions
  // 1 to 3 the loop_matches table (their loops' akaze_good and orb_good columns stand for it).
  // Version 4 and older hold float32 tiles only (version 5 also compact ones); version 5 and
  // older have no anchors table (every keyframe was kept), version 6 and older no landmarks,
  // version 7 and older no checksums (their blobs are read unverified).
  bool known = false;
  for (int v = 1; v <= kSessionFormatVersion; ++v) known = known || version == std::to_string(v);
  if (!known) {
    throw InputError(path + ": session format version " + version.substr(0, 40) +
                     ", this uwbsar reads 1 to " + std::to_string(kSessionFormatVersion));
  }
  d.format_version = std::stoi(version);
  d.source = path;
  d.config_yaml = Meta(db, "config_yaml");
  d.fingerprint = Meta(db, "config_fingerprint");
  if (config != nullptr) {
    const std::string diff = FingerprintDifference(d.fingerprint, *config);
    if (!diff.empty()) throw InputError(path + ": incompatible configuration: " + diff);
  }
  session::ReadSessionTables(db, config != nullptr ? config->limits : LimitsConfig(), &d);
  session::ReadLandmarkTables(db, &d);
  if (config != nullptr && !d.keyframes.empty()) {
    // Place recognition matches the saved features of the configured pair: a session made
    // with other detectors has nothing to match them against.
    const DetectorMap<FeatureSet>& saved = d.keyframes.front().features.by_detector;
    for (DetectorKind kind : config->place_recognition.validation.detectors) {
      if (saved.count(kind)) continue;
      std::string held;
      for (const auto& [k, f] : saved)
        held += (held.empty() ? "" : ", ") + std::string(DetectorName(k));
      throw InputError(path +
                       ": incompatible configuration: place_recognition.validation.detectors "
                       "names " +
                       DetectorName(kind) + ", the session holds features of " + held);
    }
  }
  return d;
}

}  // namespace uwbsar
