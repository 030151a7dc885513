// A saved map's walls as a run localised in it sees them (`uwbsar localize`,
// slam/localization/localizer.h): the map's line landmarks
// (place_recognition.wall_profiles.landmarks) and where its keyframes saw them. A straight wall a
// new keyframe sees, placed in the map by the keyframe's estimate, observes the landmark it lies
// on; the landmark stays where the map has it.
#pragma once

#include <map>
#include <vector>

#include "backend/line_landmark.h"
#include "core/pose2.h"
#include "frontend/wall_line_config.h"
#include "slam/session/session_data.h"
#include "slam/wall_landmarks.h"

namespace uwbsar::slam {

class MapWalls {
 public:
  MapWalls() = default;  ///< no walls
  /// The landmarks of `map` and their sightings (not rejected observations). A wall is
  /// associated within `gates` (gate_angle_deg, gate_offset_m) and `reach_m` of a sighting.
  MapWalls(const SessionData& map, const WallLineConfig& gates, double reach_m);

  bool empty() const { return lines_.empty(); }
  /// Landmark `id`'s line in the map frame; throws std::out_of_range for an unknown id.
  const Line2& Line(int id) const { return lines_.at(id); }

  /// The observations by node `node_id` of the map's landmarks that `walls` (a keyframe's, in
  /// its anchor frame) lie on when the keyframe is at T_map_anchor: a wall's angle within
  /// gate_angle_deg of the landmark's, its reference point within gate_offset_m of the
  /// landmark's line and within reach_m of one of its sightings. At most one observation per
  /// landmark (the wall nearest its line); each observation's line faces its landmark.
  std::vector<LineObservation> Observe(const std::vector<SeenLine>& walls,
                                       const Pose2& T_map_anchor, int node_id) const;

 private:
  double gate_angle_rad_ = 0.0;
  double gate_offset_m_ = 0.0;
  double reach_m_ = 0.0;
  std::map<int, Line2> lines_;
  std::map<int, std::vector<Point2>> sightings_;
};

}  // namespace uwbsar::slam
