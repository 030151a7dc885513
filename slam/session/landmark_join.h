// Wall landmarks when a run's graph becomes a session and when two sessions are joined
// (map --resume, merge): capturing them from the pose graph, and taking a new run's walls that
// lie on the saved map's for those landmarks. The file tables are slam/session/session_landmarks.h.
#pragma once

#include <map>
#include <vector>

#include "backend/pose_graph.h"
#include "frontend/wall_line_config.h"
#include "slam/session/session_data.h"

namespace uwbsar {

/// d's landmarks and line observations as `graph` holds them after its last solve: the
/// observations of its nodes, and the landmarks that some observation still sees (a wall whose
/// keyframes were all retired leaves with them).
void CaptureLandmarks(const PoseGraph& graph, SessionData* d);

/// Where each landmark's (not rejected) observations saw its wall: the point of the observed
/// line nearest its reference point, placed in the map frame by the keyframe's T_map_anchor and
/// `T_map_session`. By landmark id.
std::map<int, std::vector<Point2>> LandmarkSightings(const SessionData& s,
                                                     const Pose2& T_map_session);

/// A new run joining a saved map sees the map's walls again: each of b's landmarks that lies on
/// one of a's (b placed in a's frame by T_mapA_mapB; within config.gate_angle_deg, every one of
/// its sightings within config.gate_offset_m of a's line, and some sighting within
/// `reach_m` of one of a's) is that landmark: its observations are re-pointed to a's landmark
/// (their lines turned to face it) and it leaves b. Returns how many were reused. b's ids must
/// not collide with a's (Renumbered).
int ReuseSavedWalls(const SessionData& a, const Pose2& T_mapA_mapB, const WallLineConfig& config,
                    double reach_m, SessionData* b);

}  // namespace uwbsar
