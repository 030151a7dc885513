// What a saved session holds (docs/formats.md, "Session file"): every keyframe with its
// poses, its detected tile (what the global map is made of) and its features per detector
// (what place recognition matches), the pose graph's edges with their information, the
// loop records, the odometry of each trajectory and the configuration it was made with.
// A session may hold several trajectories (runs) in one map frame: `uwbsar map --resume`
// and `uwbsar merge` add one.
#pragma once

#include <map>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "backend/pose_graph.h"
#include "core/pose2.h"
#include "core/types.h"
#include "frontend/place_recognition/place_recognizer.h"
#include "imaging/image_grid.h"
#include "slam/session/tile_store.h"

namespace uwbsar {

/// Bumped whenever a table or column changes meaning; readers refuse versions they do not know.
/// 2: edges keep their odometry calibration fields (trajectory, path_m, turn_rad), so that a
/// resumed or merged graph calibrates each run's odometry as its own run did; 1 still reads.
/// 3: trajectories keep their recording's fingerprint; 1 and 2 still read (fingerprint "").
/// 4: loops keep their good-match counts per detector (loop_matches table) instead of the
/// akaze_good and orb_good columns, which versions 1 to 3 still read as AKAZE and ORB counts.
/// 5: a tile may be compact (slam/session/blob_codec.h EncodeTile); 1 to 4 still read (float32).
/// 6: the anchors table (keyframes the map retired, slam.place_views); 1 to 5 still read (none).
/// 7: the landmarks and line_observations tables (walls as line landmarks,
/// place_recognition.wall_profiles.landmarks); 1 to 6 still read (none).
/// 8: every blob has a checksum column beside it (blob_checksum.h) and every run a fingerprint
/// (kUnknownRunFingerprint where none is known); 1 to 7 still read (blobs unverified, an empty
/// fingerprint read as unknown).
constexpr int kSessionFormatVersion = 8;

struct SessionKeyframe {
  int id = 0;          ///< unique in the session (graph node id)
  int trajectory = 0;  ///< which run it belongs to (SessionTrajectory::id)
  TimestampNs stamp_ns = 0;
  Pose2 T_odom_anchor;  ///< the tile frame in its run's odometry frame
  Pose2 T_odom_robot;   ///< the robot at stamp_ns, same frame
  Pose2 T_map_anchor;   ///< optimised pose of the tile frame in the session's map frame
  double path_begin_m = 0.0, path_end_m = 0.0;  ///< its run's odometry path
  bool fixed = false;                           ///< held constant (the gauge)
  TileRef detected;           ///< CV_32FC1 detected tile, map resolution: a live run's stays in its
                              ///< tile store (slam/session/tile_store.h), read back one at a time
  ImageGrid detected_grid;    ///< its geometry in the anchor frame
  KeyframeFeatures features;  ///< per detector (validation.detectors when it was made; AKAZE
                              ///< and ORB in every session before them) at the feature
                              ///< resolution (own grid)
};

/// A keyframe the map retired (slam.place_views): no tile, no features, no node; what places its
/// run's trajectory between the keyframes kept (session_outputs.h CorrectedTrajectory).
struct SessionAnchor {
  int id = 0;  ///< unique in the session, never a keyframe's
  int trajectory = 0;
  TimestampNs stamp_ns = 0;
  Pose2 T_odom_anchor;  ///< the tile frame in its run's odometry frame
  int hub_id = -1;      ///< the kept keyframe it follows; -1: T_hub_anchor is in the map frame
  Pose2 T_hub_anchor;   ///< its pose in the hub's frame

  /// Its pose in the map frame, from the keyframes' (`poses` by id).
  std::optional<Pose2> MapPose(const std::map<int, Pose2>& poses) const;
};

struct SessionLoop {
  int query_id = 0;  ///< the newer keyframe (j)
  int match_id = 0;  ///< the older keyframe (i)
  bool validated = false;
  bool accepted = false;  ///< validated and kept by the backend
  Pose2 T_ij;             ///< pose of j in i (validated loops)
  double chi2 = 0.0;
  DetectorMap<int> good_matches;  ///< per detector of the validation pair
  std::string reason;
};

struct SessionOdometry {
  int trajectory = 0;
  TimestampNs stamp_ns = 0;
  Pose2 T_odom_robot;
  double path_m = 0.0;
};

/// How the file (from format version 8) stores the fingerprint of a run mapped before format
/// version 3, whose identity is unknown (SessionTrajectory::fingerprint ""): never empty, so
/// that a NULL or empty fingerprint is damage, refused, and never a new run.
inline constexpr const char* kUnknownRunFingerprint = "unknown: mapped before session format 3";

struct SessionTrajectory {
  int id = 0;
  std::string input;  ///< what was mapped (bag path or simulation description)
  /// Identity of the recording it was mapped from (RunFingerprint: storage id, first and last
  /// stamps, message count), so that joining the same recording twice is refused; "" (unknown)
  /// for runs mapped before format version 3 (kUnknownRunFingerprint in the file).
  std::string fingerprint;
};

struct SessionEdge {
  PoseGraphEdge edge;
  bool rejected = false;  ///< loops the backend rejected at the last solve
};

/// A wall landmark of the map (backend/line_landmark.h), in the session's map frame.
struct SessionLandmark {
  int id = 0;  ///< unique in the session
  Line2 line_map;
};

/// One keyframe's observation of a landmark (LineObservation::node_id is the keyframe's id).
struct SessionLineObservation {
  LineObservation observation;
  bool rejected = false;  ///< the backend rejected it at the last solve
};

struct SessionData {
  int format_version = kSessionFormatVersion;
  std::string config_yaml;  ///< the whole configuration it was made with
  std::string fingerprint;  ///< ConfigFingerprint of that configuration
  /// The file it was read from (errors about what it implies name it); "" for a run captured
  /// in memory. A join keeps the saved session's.
  std::string source;
  std::vector<SessionTrajectory> trajectories;
  std::vector<SessionKeyframe> keyframes;  ///< by trajectory, then in time
  std::vector<SessionEdge> edges;
  std::vector<SessionLoop> loops;
  std::vector<SessionOdometry> odometry;                  ///< by trajectory, then in time
  std::vector<SessionAnchor> anchors;                     ///< by trajectory, then in time
  std::vector<SessionLandmark> landmarks;                 ///< by id
  std::vector<SessionLineObservation> line_observations;  ///< in the pose graph's order

  const SessionKeyframe* Find(int id) const;
  int MaxKeyframeId() const;    ///< -1 when empty (anchors' ids included: never reused)
  int MaxTrajectoryId() const;  ///< -1 when empty
  int MaxLandmarkId() const;    ///< -1 when empty
  /// Optimised T_map_anchor by keyframe id.
  std::map<int, Pose2> Poses() const;
  /// The runs that have keyframes, in the order of their first keyframe; with runs that only
  /// have anchors (every keyframe retired by a later run), all of them in the trajectories'
  /// order.
  std::vector<int> TrajectoryIds() const;
};

/// `s` with dense ids: keyframes 0..n-1 in their order, trajectories 0..m-1 in theirs, and
/// every reference (edges, loops, odometry, features) renumbered with them.
SessionData WithDenseIds(const SessionData& s);

}  // namespace uwbsar
