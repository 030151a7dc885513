// Wall landmarks of one trajectory (place_recognition.wall_profiles.landmarks): the straight
// walls each keyframe sees (frontend/wall_line.h) are associated, keyframe after keyframe, into
// tracks, one per wall; a track seen by min_observations keyframes becomes a line landmark of
// the pose graph (backend/line_landmark.h), and every keyframe of the track observes it.
//
// Association works in the odometry's frame, between a keyframe and the track's last sighting
// at most max_gap keyframes before it: over a few metres the odometry is good to a few
// millimetres and a fraction of a degree, so the gates (gate_offset_m, gate_angle_deg) can be
// tight; the track follows its wall sighting by sighting, so the odometry's slow heading drift
// along a 20 m corridor never leaves the gate. Whether the wall really is straight along the
// whole track is the graph's to judge: an observation that does not fit the line is rejected
// by its chi2 there.
#pragma once

#include <deque>
#include <map>
#include <opencv2/core.hpp>
#include <utility>
#include <vector>

#include "backend/backend_config.h"
#include "backend/line_landmark.h"
#include "core/pose2.h"
#include "frontend/keyframe.h"
#include "frontend/keyframe_products.h"
#include "frontend/wall_line.h"
#include "frontend/wall_profile_config.h"

namespace uwbsar::slam {

/// A wall a keyframe sees, in its anchor frame.
struct SeenLine {
  Line2 line_anchor;
  Point2 reference_anchor;  ///< where along the wall the keyframe saw it
  double offset_std_m = 0.02;
  double normal_std_rad = 0.017;
};

/// The lines of FindWallLines for a robot heading `heading_anchor_rad` in the anchor frame, each
/// with its reference point: the point of the line nearest the middle of the stretch of path
/// along which the tile saw it.
std::vector<SeenLine> SeenLines(const std::vector<WallLineObservation>& lines,
                                double heading_anchor_rad);

/// A keyframe's wall lines (frontend/keyframe_products.h) as SeenLines; none without them.
std::vector<SeenLine> SeenLines(const KeyframeProducts& products);

/// Walls as landmarks (place_recognition.wall_profiles.landmarks): only for a base whose
/// odometry calibration is given (backend.odometry_calibration), unless
/// require_calibrated_base is off.
bool UsesWallLandmarks(const WallProfileConfig& walls, const BackendConfig& backend);

class WallLandmarkTracker {
 public:
  /// Landmark ids are handed out from `first_landmark_id` up.
  explicit WallLandmarkTracker(const WallProfileConfig& config, int first_landmark_id = 0)
      : config_(config.landmarks), next_id_(first_landmark_id) {}

  struct Update {
    /// Landmarks that enter the graph now, with their line in the odometry's world frame (the
    /// graph re-seeds them from their first observation's node).
    std::vector<std::pair<int, Line2>> new_landmarks;
    /// Observations for the graph: this keyframe's of landmarks already in it, and the
    /// earlier keyframes' of the landmarks that enter now.
    std::vector<LineObservation> observations;
  };

  /// The walls of `keyframe`, its wall lines among `products` (none for a tile cut short).
  Update Add(const Keyframe& keyframe, const KeyframeProducts& products);

  /// The walls keyframe `keyframe_id` sees; T_world_anchor is its anchor's odometry pose.
  /// Keyframes come in path order, one call each (an empty `lines` counts towards the gap).
  Update Add(int keyframe_id, const Pose2& T_world_anchor, const std::vector<SeenLine>& lines);

  /// Whether keyframes `a_id` and `b_id` (both among the last 16 added) saw one wall that is a
  /// landmark of the graph by now: what a wall edge between them would measure is then in the
  /// graph already (slam/slam_system.cc keeps the edges only between keyframes that do not).
  bool ShareLandmark(int a_id, int b_id) const;

  int tracks_started() const { return tracks_started_; }
  int lines_seen() const { return lines_seen_; }
  int next_landmark_id() const { return next_id_; }

 private:
  struct Track {
    int serial = 0;                        ///< tracks_started_ when it began
    int id = -1;                           ///< landmark id once in the graph, -1 before
    Line2 last_world;                      ///< the last sighting, in the odometry's world frame
    int last_seen = 0;                     ///< the call that saw it last
    std::vector<LineObservation> waiting;  ///< sightings before it enters the graph
  };

  const WallLineConfig config_;
  int next_id_ = 0;
  int lines_seen_ = 0;
  int calls_ = 0;
  int tracks_started_ = 0;
  std::vector<Track> tracks_;
  std::deque<std::pair<int, std::vector<int>>> recent_;  ///< keyframe id -> its tracks' serials
  std::map<int, int> landmark_of_serial_;  ///< tracks of the recent keyframes that are landmarks
};

}  // namespace uwbsar::slam
