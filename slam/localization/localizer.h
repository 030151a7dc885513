// Localisation in a saved map (`uwbsar localize`). The map is fixed:
// nothing is added to it. Each new keyframe (odometry pose, AKAZE/ORB features) is matched
// against the map's keyframes: while the robot is not placed, against all of them (global
// search) and it is placed once session.connect_min_loops validated loops agree on where
// its odometry frame lies; while tracking, against the map keyframes near its estimate,
// keeping only loops that agree with the estimate. A sliding window of the last
// session.localize_window_keyframes keyframes (odometry edges between them, loop edges to
// the fixed map keyframes) is optimised after each keyframe with loops. Without a loop for
// session.localize_lost_after_m of path the robot is "lost" and global search resumes.
//
// The map's walls (its line landmarks, place_recognition.wall_profiles.landmarks) hold the
// robot between loops: once placed, each straight wall a keyframe sees that lies on one of the
// map's (within the landmark gates at the estimate, and within two tile lengths of where the
// map saw it) observes that landmark, held fixed in the window; a keyframe with such walls is
// optimised too. Along a corridor, where loops are few, they keep the estimate on its line.
//
// Once placed, each keyframe is also registered against the map tiles nearest where it is
// predicted to be (place_recognition.registration, frontend/place_recognition/map_registration.h):
// every pixel both tiles observed, not a few dozen keypoints, so the robot keeps tracking when
// objects moved since the map was made. A distinct registration is a constraint into the map, as
// a loop is, and counts as evidence that keeps the robot from being "lost".
#pragma once

#include <deque>
#include <list>
#include <string>
#include <unordered_map>
#include <vector>

#include "frontend/place_recognition/map_registration.h"
#include "frontend/place_recognition/place_recognizer.h"
#include "slam/map_walls.h"
#include "slam/session/session_data.h"
#include "slam/session/session_settings.h"

namespace uwbsar {

enum class LocalizeStatus { kTracking, kLost, kRelocalised };
/// "tracking", "lost" (not placed yet, or no loop for a while), "relocalised" (placed here).
const char* LocalizeStatusName(LocalizeStatus status);

struct LocalizedKeyframe {
  int id = 0;
  TimestampNs stamp_ns = 0;
  double path_end_m = 0.0;
  Pose2 T_odom_anchor;
  Pose2 T_map_anchor;   ///< estimate (valid once placed)
  bool placed = false;  ///< the robot had been placed when this keyframe was decided
  LocalizeStatus status = LocalizeStatus::kLost;
  int candidates = 0;
  int loops = 0;          ///< validated loops into the map used for this keyframe
  int registrations = 0;  ///< distinct registrations against map tiles used (once placed)
  int walls = 0;          ///< the map's wall landmarks it observed (once placed)
};

class Localizer {
 public:
  /// `map` must outlive the localizer.
  Localizer(const SessionData& map, const SessionSettings& config);

  /// One new keyframe: its features (grid, centre) and odometry anchor pose, its stamp, the
  /// odometry path at its end, the straight walls its tile shows (slam/wall_landmarks.h,
  /// anchor frame) and its tile as registration compares it (MakeRegistrationImage of its
  /// detected tile; empty: not registered). Returns what was decided for it.
  const LocalizedKeyframe& Add(const KeyframeFeatures& features, const Pose2& T_odom_anchor,
                               TimestampNs stamp_ns, double path_end_m,
                               const std::vector<slam::SeenLine>& walls = {},
                               const RegistrationImage& image = {});

  /// Whether the map has wall landmarks that Add's `walls` can observe (and the configuration
  /// uses them): the caller need not find a tile's walls otherwise.
  bool UsesWalls() const { return !map_walls_.empty(); }
  /// Whether Add's `image` is used (place_recognition.registration.enabled).
  bool UsesRegistration() const { return pr_.registration.enabled; }

  const std::vector<LocalizedKeyframe>& keyframes() const { return keyframes_; }
  bool placed() const { return placed_; }
  /// The current map <- odometry correction (identity before the first fix).
  const Pose2& T_map_odom() const { return T_map_odom_; }

 private:
  struct Loop {
    int map_id = 0;
    int keyframe_index = 0;  ///< into keyframes_
    Pose2 T_ij;
    Eigen::Matrix3d information;
    Pose2 T_map_odom;  ///< where this loop puts the odometry frame
  };
  /// The validated loops of a new keyframe (keyframes_[index] once added) with the map:
  /// candidates are every map keyframe (`global`) or those near the current estimate;
  /// `candidates` counts the pairs matched.
  std::vector<Loop> MatchMap(const KeyframeFeatures& features, const Pose2& T_odom_anchor,
                             int index, bool global, int* candidates) const;
  /// (Re-)placement: keeps `found` among the recent unplaced loops; when enough of them agree,
  /// sets T_map_odom_ and returns the agreeing loops, else none. Sets out->status.
  std::vector<Loop> Place(const std::vector<Loop>& found, LocalizedKeyframe* out);
  /// The distinct registrations of keyframes_[index] (`image`, centre `centre_anchor`) against
  /// the map tiles nearest its estimate, as loops.
  std::vector<Loop> RegisterWithMap(const RegistrationImage& image, const Point2& centre_anchor,
                                    const Pose2& T_odom_anchor, int index);
  /// The registration image of map keyframe `m` (made from its tile once, kept in a small
  /// least-recently-used cache).
  const RegistrationImage& MapImage(const SessionKeyframe& m);
  void SolveWindow();

  const SessionData& map_;
  SessionSettings config_;
  PlaceRecognitionConfig pr_;
  std::vector<LocalizedKeyframe> keyframes_;
  std::deque<Loop> window_loops_;             ///< loops of the keyframes in the window
  std::deque<LineObservation> window_walls_;  ///< ... and their walls (node_id: keyframe index)
  slam::MapWalls map_walls_;                  ///< the map's walls, empty when not used
  std::vector<Loop> unplaced_;                ///< validated loops while not placed (recent ones)
  bool placed_ = false;
  Pose2 T_map_odom_;
  double path_at_last_loop_m_ = 0.0;
  // The map keyframes' registration images by id, most recently used first in map_image_order_.
  std::unordered_map<int, std::pair<RegistrationImage, std::list<int>::iterator>> map_images_;
  std::list<int> map_image_order_;
};

}  // namespace uwbsar
