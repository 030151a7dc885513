#include "slam/session/session_reader.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <map>
#include <set>
#include <tuple>
#include <utility>

#include "core/errors.h"
#include "slam/session/blob_checksum.h"
#include "slam/session/blob_codec.h"
#include "slam/session/session_loops.h"
#include "slam/session/table_reader.h"

namespace uwbsar::session {
namespace {

constexpr std::int64_t kMaxStamp = std::numeric_limits<std::int64_t>::max();

/// x_m, y_m, yaw_rad columns named `prefix`x_m ... (NULL, non-finite or beyond the bounds
/// refused).
Pose2 ReadPose(const TableReader& t, const std::string& prefix) {
  Pose2 p;
  p.x_m = t.Real(prefix + "x_m", -kMaxCoordinateM, kMaxCoordinateM);
  p.y_m = t.Real(prefix + "y_m", -kMaxCoordinateM, kMaxCoordinateM);
  p.yaw_rad = t.Real(prefix + "yaw_rad", -kMaxAngleRad, kMaxAngleRad);
  return p;
}

double Resolution(const TableReader& t, const std::string& column) {
  return t.Real(column, kMinResolutionM, kMaxResolutionM);
}

/// A run's fingerprint (format version 3 on): what tells a join that a recording is already in
/// the map, so a missing one is refused, never read as a new run. NULL was never written;
/// versions 3 to 7 wrote "" for a run carried over from a version 1 or 2 session, version 8
/// kUnknownRunFingerprint (read as "").
std::string Fingerprint(const TableReader& t, int format_version) {
  const std::string f = t.Text("fingerprint");
  if (format_version >= kFirstChecksummedVersion) {
    if (f.empty()) t.Refuse("fingerprint", "is empty");
    if (f == kUnknownRunFingerprint) return "";
  }
  return f;
}

/// The trajectories table, by id; format version 3 adds the recordings' fingerprints.
void ReadTrajectories(SqliteDb& db, SessionData* d) {
  std::vector<std::string> required = {"id", "input"};
  if (d->format_version >= 3) required.push_back("fingerprint");
  TableReader t(db, "trajectories", required);
  std::set<int> ids;
  while (t.Next()) {
    SessionTrajectory s;
    s.id = t.Id("id");
    if (!ids.insert(s.id).second) t.Refuse("id", std::to_string(s.id) + " appears twice");
    s.input = t.Text("input");
    if (t.Has("fingerprint")) s.fingerprint = Fingerprint(t, d->format_version);
    d->trajectories.push_back(s);
  }
  std::stable_sort(
      d->trajectories.begin(), d->trajectories.end(),
      [](const SessionTrajectory& a, const SessionTrajectory& b) { return a.id < b.id; });
}

bool HasTrajectory(const SessionData& d, int id) {
  for (const SessionTrajectory& t : d.trajectories) {
    if (t.id == id) return true;
  }
  return false;
}

/// A trajectory column: an id of the trajectories table.
int TrajectoryRef(const TableReader& t, const std::string& column, const SessionData& d) {
  const int id = t.Id(column);
  if (!HasTrajectory(d, id)) t.Refuse(column, std::to_string(id) + " is not a trajectory");
  return id;
}

/// One row of the keyframes table, its blobs within `limits`.
SessionKeyframe ReadKeyframeRow(const TableReader& t, const SessionData& d,
                                const LimitsConfig& limits) {
  SessionKeyframe k;
  k.id = t.Id("id");
  k.trajectory = TrajectoryRef(t, "trajectory", d);
  k.stamp_ns = static_cast<TimestampNs>(t.Integer("stamp_ns", 0, kMaxStamp));
  k.T_odom_anchor = ReadPose(t, "odom_");
  k.T_odom_robot = ReadPose(t, "robot_");
  k.T_map_anchor = ReadPose(t, "");
  k.fixed = t.Flag("fixed");
  k.path_begin_m = t.Real("path_begin_m", -kMaxPathM, kMaxPathM);
  k.path_end_m = t.Real("path_end_m", -kMaxPathM, kMaxPathM);
  k.detected_grid.x0_m = t.Real("tile_x0_m", -kMaxCoordinateM, kMaxCoordinateM);
  k.detected_grid.y0_m = t.Real("tile_y0_m", -kMaxCoordinateM, kMaxCoordinateM);
  k.detected_grid.resolution_m = Resolution(t, "tile_resolution_m");
  MatBudget tile_budget;
  tile_budget.max_pixels = limits.max_tile_pixels;
  const cv::Mat tile =
      DecodeTile(t.Blob("tile", "keyframe " + std::to_string(k.id)), t.Where("tile"), tile_budget);
  if (tile.empty()) t.Refuse("tile", "is empty");
  if (!cv::checkRange(tile)) t.Refuse("tile", "has non-finite pixels");
  k.detected_grid.rows = tile.rows;
  k.detected_grid.cols = tile.cols;
  k.detected = TileRef(tile);
  KeyframeFeatures& kf = k.features;
  kf.id = k.id;
  kf.grid.x0_m = t.Real("feature_x0_m", -kMaxCoordinateM, kMaxCoordinateM);
  kf.grid.y0_m = t.Real("feature_y0_m", -kMaxCoordinateM, kMaxCoordinateM);
  kf.grid.resolution_m = Resolution(t, "feature_resolution_m");
  kf.grid.rows = static_cast<int>(t.Integer("feature_rows", 1, 1 << 20));
  kf.grid.cols = static_cast<int>(t.Integer("feature_cols", 1, 1 << 20));
  if (static_cast<double>(kf.grid.rows) * kf.grid.cols > limits.max_tile_pixels) {
    t.Refuse("feature_cols", std::to_string(kf.grid.rows) + " x " + std::to_string(kf.grid.cols) +
                                 " pixels are more than limits.max_tile_pixels");
  }
  kf.centre_anchor.x_m = t.Real("centre_x_m", -kMaxCoordinateM, kMaxCoordinateM);
  kf.centre_anchor.y_m = t.Real("centre_y_m", -kMaxCoordinateM, kMaxCoordinateM);
  kf.path_begin_m = k.path_begin_m;
  kf.T_world_anchor = k.T_map_anchor;
  return k;
}

/// "AKAZE, ORB": the detectors of `k`'s features ("no features" when none).
std::string DetectorList(const KeyframeFeatures& k) {
  std::string out;
  for (const auto& [kind, f] : k.by_detector)
    out += (out.empty() ? "" : ", ") + std::string(DetectorName(kind));
  return out.empty() ? "no features" : "features of " + out;
}

/// One row of the features table (its keypoints and descriptors within `limits`).
FeatureSet ReadFeatureRow(const TableReader& t, int id, DetectorKind kind,
                          const LimitsConfig& limits) {
  const std::string owner = "keyframe " + std::to_string(id) + " (" + DetectorName(kind) + ")";
  FeatureSet f;
  f.detector = kind;
  f.norm_type = static_cast<int>(t.Integer("norm_type", 0, 64));
  if (f.norm_type != cv::NORM_L1 && f.norm_type != cv::NORM_L2 && f.norm_type != cv::NORM_L2SQR &&
      f.norm_type != cv::NORM_HAMMING && f.norm_type != cv::NORM_HAMMING2) {
    t.Refuse("norm_type", std::to_string(f.norm_type) + " is not a descriptor norm");
  }
  f.keypoints = DecodeKeypoints(t.Blob("keypoints", owner), t.Where("keypoints"));
  for (const cv::KeyPoint& k : f.keypoints) {
    if (!std::isfinite(k.pt.x) || !std::isfinite(k.pt.y) || !std::isfinite(k.size) ||
        !std::isfinite(k.angle) || !std::isfinite(k.response)) {
      t.Refuse("keypoints", "hold a non-finite keypoint");
    }
  }
  MatBudget budget;
  budget.types = {CV_8UC1, CV_32FC1};
  budget.max_pixels = limits.max_tile_pixels;
  f.descriptors = DecodeMat(t.Blob("descriptors", owner), t.Where("descriptors"), budget);
  if (f.descriptors.rows != f.size()) {
    t.Refuse("descriptors", std::to_string(f.descriptors.rows) + " rows for " +
                                std::to_string(f.size()) + " keypoints");
  }
  if (f.descriptors.depth() == CV_32F && !cv::checkRange(f.descriptors)) {
    t.Refuse("descriptors", "hold non-finite values");
  }
  return f;
}

/// The features table: one row per keyframe of `d` and detector; every keyframe needs rows of
/// the same detectors (those the session was made with; AKAZE and ORB before
/// validation.detectors), and rows of other keyframes are refused.
void ReadFeatures(SqliteDb& db, const LimitsConfig& limits, SessionData* d) {
  std::map<int, SessionKeyframe*> by_id;
  for (SessionKeyframe& k : d->keyframes) by_id[k.id] = &k;
  TableReader t(db, "features",
                WithChecksums(d->format_version,
                              {"keyframe_id", "detector", "norm_type", "keypoints", "descriptors"},
                              {"keypoints", "descriptors"}));
  while (t.Next()) {
    const int id = t.Id("keyframe_id");
    const auto it = by_id.find(id);
    if (it == by_id.end()) t.Refuse("keyframe_id", std::to_string(id) + " is not a keyframe");
    const std::string name = t.Text("detector");
    DetectorKind kind = DetectorKind::kAkaze;
    if (!ParseDetector(name, &kind))
      t.Refuse("detector", "'" + name.substr(0, 40) + "' is not a detector");
    DetectorMap<FeatureSet>& sets = it->second->features.by_detector;
    if (sets.count(kind)) {
      t.Refuse("detector", name + " of keyframe " + std::to_string(id) + " appears twice");
    }
    sets[kind] = ReadFeatureRow(t, id, kind, limits);
  }
  for (const SessionKeyframe& k : d->keyframes) {
    const SessionKeyframe& first = d->keyframes.front();
    if (k.features.by_detector.empty() ||
        DetectorList(k.features) != DetectorList(first.features)) {
      throw InputError(db.path() + ": features: keyframe " + std::to_string(k.id) + " has " +
                       DetectorList(k.features) + ", keyframe " + std::to_string(first.id) + " " +
                       DetectorList(first.features));
    }
  }
}

/// The keyframes table (sorted by trajectory, time and id) with their features.
void ReadKeyframes(SqliteDb& db, const LimitsConfig& limits, SessionData* d) {
  std::vector<std::string> columns = {"id",
                                      "trajectory",
                                      "stamp_ns",
                                      "odom_x_m",
                                      "odom_y_m",
                                      "odom_yaw_rad",
                                      "robot_x_m",
                                      "robot_y_m",
                                      "robot_yaw_rad",
                                      "x_m",
                                      "y_m",
                                      "yaw_rad",
                                      "fixed",
                                      "path_begin_m",
                                      "path_end_m",
                                      "tile_x0_m",
                                      "tile_y0_m",
                                      "tile_resolution_m",
                                      "tile",
                                      "feature_x0_m",
                                      "feature_y0_m",
                                      "feature_resolution_m",
                                      "feature_rows",
                                      "feature_cols",
                                      "centre_x_m",
                                      "centre_y_m"};
  TableReader t(db, "keyframes", WithChecksums(d->format_version, columns, {"tile"}));
  std::set<int> ids;
  while (t.Next()) {
    SessionKeyframe k = ReadKeyframeRow(t, *d, limits);
    if (!ids.insert(k.id).second) t.Refuse("id", std::to_string(k.id) + " appears twice");
    d->keyframes.push_back(std::move(k));
  }
  std::stable_sort(d->keyframes.begin(), d->keyframes.end(),
                   [](const SessionKeyframe& a, const SessionKeyframe& b) {
                     return std::tie(a.trajectory, a.stamp_ns, a.id) <
                            std::tie(b.trajectory, b.stamp_ns, b.id);
                   });
  ReadFeatures(db, limits, d);
}

/// 9 doubles, row-major: finite, symmetric and positive definite (as the pose graph needs).
Eigen::Matrix3d ReadInformation(const TableReader& t, std::int64_t idx) {
  const std::vector<unsigned char> info = t.Blob("information", "edge " + std::to_string(idx));
  if (info.size() != 9 * sizeof(double)) {
    t.Refuse("information", "holds " + std::to_string(info.size()) + " bytes, not 9 doubles");
  }
  double v[9];
  std::memcpy(v, info.data(), sizeof(v));
  Eigen::Matrix3d m;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) m(r, c) = v[r * 3 + c];
  const double scale = m.allFinite() ? m.cwiseAbs().maxCoeff() : 0.0;
  const bool symmetric = scale > 0.0 && (m - m.transpose()).cwiseAbs().maxCoeff() <= 1e-9 * scale;
  const Eigen::LLT<Eigen::Matrix3d> llt(m);
  if (!symmetric || llt.info() != Eigen::Success ||
      llt.matrixU().toDenseMatrix().diagonal().minCoeff() <= 1e-9 * std::sqrt(scale)) {
    t.Refuse("information", "is not a finite symmetric positive definite matrix");
  }
  return m;
}

/// The edges table in its order (idx); version 1 lacks the calibration columns.
void ReadEdges(SqliteDb& db, SessionData* d) {
  std::vector<std::string> columns = {"idx", "from_id", "to_id",       "kind",    "x_m",
                                      "y_m", "yaw_rad", "information", "rejected"};
  if (d->format_version >= 2) columns.insert(columns.end(), {"trajectory", "path_m", "turn_rad"});
  TableReader t(db, "edges", WithChecksums(d->format_version, columns, {"information"}));
  std::set<int> keyframes;
  for (const SessionKeyframe& k : d->keyframes) keyframes.insert(k.id);
  std::vector<std::pair<std::int64_t, SessionEdge>> edges;
  while (t.Next()) {
    SessionEdge e;
    const std::int64_t idx = t.Integer("idx", 0, INT_MAX);
    e.edge.from_id = KeyframeRef(t, "from_id", keyframes);
    e.edge.to_id = KeyframeRef(t, "to_id", keyframes);
    if (e.edge.to_id == e.edge.from_id) t.Refuse("to_id", "equals from_id");
    const std::string kind = t.Text("kind");
    if (kind == EdgeKindName(EdgeKind::kOdometry)) {
      e.edge.kind = EdgeKind::kOdometry;
    } else if (kind == EdgeKindName(EdgeKind::kLoop)) {
      e.edge.kind = EdgeKind::kLoop;
    } else if (kind == EdgeKindName(EdgeKind::kWall)) {
      e.edge.kind = EdgeKind::kWall;
    } else if (kind == EdgeKindName(EdgeKind::kMarginal)) {
      e.edge.kind = EdgeKind::kMarginal;
    } else {
      t.Refuse("kind", "'" + kind.substr(0, 40) + "' is not an edge kind");
    }
    e.edge.T_from_to = ReadPose(t, "");
    e.edge.information = ReadInformation(t, idx);
    e.rejected = t.Flag("rejected");
    if (d->format_version >= 2) {
      e.edge.trajectory = static_cast<int>(t.Integer("trajectory", -1, INT_MAX));
      if (e.edge.trajectory >= 0 && !HasTrajectory(*d, e.edge.trajectory)) {
        t.Refuse("trajectory", std::to_string(e.edge.trajectory) + " is not a trajectory");
      }
      e.edge.path_m = t.Real("path_m", -kMaxPathM, kMaxPathM);
      e.edge.turn_rad = t.RealOrNaN("turn_rad", -kMaxAngleRad, kMaxAngleRad);  // NULL: NaN
    }
    edges.emplace_back(idx, e);
  }
  std::stable_sort(edges.begin(), edges.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  for (const auto& [idx, e] : edges) d->edges.push_back(e);
}

/// The odometry table, by trajectory and time: each run's rows in strictly increasing time, as
/// written (the odometry buffer drops a sample not after the one before).
void ReadOdometry(SqliteDb& db, SessionData* d) {
  TableReader t(db, "odometry", {"trajectory", "stamp_ns", "x_m", "y_m", "yaw_rad", "path_m"});
  std::map<int, std::pair<std::int64_t, TimestampNs>> last;  // by trajectory: row, stamp
  while (t.Next()) {
    SessionOdometry o;
    o.trajectory = TrajectoryRef(t, "trajectory", *d);
    o.stamp_ns = static_cast<TimestampNs>(t.Integer("stamp_ns", 0, kMaxStamp));
    const auto before = last.find(o.trajectory);
    if (before != last.end() && o.stamp_ns <= before->second.second) {
      t.Refuse("stamp_ns", std::to_string(o.stamp_ns) + " is not after row " +
                               std::to_string(before->second.first) + "'s (" +
                               std::to_string(before->second.second) + ") of trajectory " +
                               std::to_string(o.trajectory));
    }
    last[o.trajectory] = {t.row(), o.stamp_ns};
    o.T_odom_robot = ReadPose(t, "");
    o.path_m = t.Real("path_m", -kMaxPathM, kMaxPathM);
    d->odometry.push_back(o);
  }
  std::stable_sort(d->odometry.begin(), d->odometry.end(),
                   [](const SessionOdometry& a, const SessionOdometry& b) {
                     return std::tie(a.trajectory, a.stamp_ns) < std::tie(b.trajectory, b.stamp_ns);
                   });
}

/// The anchors table (format version 6): keyframes the map retired, by trajectory and time.
void ReadAnchors(SqliteDb& db, SessionData* d) {
  if (d->format_version < 6) return;
  TableReader t(db, "anchors",
                {"id", "trajectory", "stamp_ns", "odom_x_m", "odom_y_m", "odom_yaw_rad", "hub_id",
                 "x_m", "y_m", "yaw_rad"});
  std::set<int> ids;
  for (const SessionKeyframe& k : d->keyframes) ids.insert(k.id);
  const std::set<int> keyframes = ids;
  while (t.Next()) {
    SessionAnchor a;
    a.id = t.Id("id");
    if (!ids.insert(a.id).second) t.Refuse("id", std::to_string(a.id) + " is already used");
    a.trajectory = TrajectoryRef(t, "trajectory", *d);
    a.stamp_ns = static_cast<TimestampNs>(t.Integer("stamp_ns", 0, kMaxStamp));
    a.T_odom_anchor = ReadPose(t, "odom_");
    a.hub_id = static_cast<int>(t.Integer("hub_id", -1, INT_MAX));
    if (a.hub_id >= 0 && !keyframes.count(a.hub_id))
      t.Refuse("hub_id", std::to_string(a.hub_id) + " is not a keyframe");
    a.T_hub_anchor = ReadPose(t, "");
    d->anchors.push_back(a);
  }
  std::stable_sort(d->anchors.begin(), d->anchors.end(),
                   [](const SessionAnchor& a, const SessionAnchor& b) {
                     return std::tie(a.trajectory, a.stamp_ns) < std::tie(b.trajectory, b.stamp_ns);
                   });
}

}  // namespace

int KeyframeRef(const TableReader& t, const std::string& column, const std::set<int>& keyframes) {
  const int id = t.Id(column);
  if (!keyframes.count(id)) t.Refuse(column, std::to_string(id) + " is not a keyframe");
  return id;
}

void ReadSessionTables(SqliteDb& db, const LimitsConfig& limits, SessionData* d) {
  ReadTrajectories(db, d);
  ReadKeyframes(db, limits, d);
  ReadEdges(db, d);
  ReadLoopTables(db, d);
  ReadOdometry(db, d);
  ReadAnchors(db, d);
}

}  // namespace uwbsar::session
