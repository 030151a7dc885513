// Keyframes bounded by the area mapped, not the hours driven: which keyframe a revisit retires.
//
// A place is where a keyframe's anchor lies, seen with the robot heading one way. Every
// keyframe that a new one revisits (its anchor within radius_m, the robot's heading within
// heading_deg, and not the same pass: min_separation_m of path apart on one run, or another
// run) is a view of that place. When the new keyframe, once a loop tied it to the map, makes
// more than max_per_place views, the oldest view is retired (the newer one wins: a building
// changes, furniture moves, doors close). SlamSystem folds a retired keyframe out of the pose
// graph (PoseGraph::RemoveNode), drops its tile and features, and keeps its pose relative to
// the hub node, so that the trajectory of the run stays corrected where the map has moved on.
#pragma once

#include <functional>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "backend/pose_graph.h"
#include "core/pose2.h"
#include "slam/config/place_views_config.h"

namespace uwbsar {

/// A kept keyframe as the choice sees it.
struct PlaceView {
  int id = 0;
  int trajectory = 0;
  Point2 anchor_world;           ///< optimised position of its anchor
  double robot_heading_rad = 0;  ///< optimised heading of the robot at its middle
  double path_mid_m = 0.0;       ///< its run's odometry path at its middle
  long long stamp = 0;           ///< order of age (larger: newer)
  bool retirable = true;         ///< false for the gauge
};

/// The views of `query`'s place among `kept` (query excluded), oldest first.
std::vector<const PlaceView*> ViewsOfPlace(const std::vector<PlaceView>& kept,
                                           const PlaceView& query, const PlaceViewsConfig& config);

/// The keyframe `query` retires: the oldest retirable view of its place when the place then
/// holds more than max_per_place views; nothing otherwise (or with max_per_place 0).
std::optional<int> KeyframeToRetire(const std::vector<PlaceView>& kept, const PlaceView& query,
                                    const PlaceViewsConfig& config);

/// The keyframes an accepted loop ties to the map, from a solve's edge reports: only such a
/// keyframe says where it is well enough to stand for a place.
std::set<int> TiedByAcceptedLoops(const std::vector<EdgeReport>& reports);

/// For each of `queries` (in order) still in `views` and in `tied`: KeyframeToRetire, then
/// `retire(victim)`, which returns false when it could not retire it (the view then stays).
/// Retired views leave `views`.
void RetireRevisitedViews(std::vector<PlaceView>* views, const std::vector<int>& queries,
                          const std::set<int>& tied, const PlaceViewsConfig& config,
                          const std::function<bool(int)>& retire);

}  // namespace uwbsar
