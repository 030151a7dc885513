// Keyframes bounded by area across runs: when a run joins a saved map (`uwbsar map --resume`,
// `uwbsar merge`), its keyframes are new views of the places the map already holds. After the
// join is solved, each new keyframe that an accepted loop ties to the map counts the views of
// its place among all keyframes, saved and new, and beyond slam.place_views.max_per_place the
// oldest is retired (slam/session/place_views.h), as SlamSystem does within one run: the newer
// view wins, so a map resumed every day keeps the building's current state and its size
// follows the area, not the days.
#pragma once

#include <vector>

#include "backend/pose_graph.h"
#include "slam/config/place_views_config.h"
#include "slam/session/session_data.h"

namespace uwbsar {

/// Retires views from the solved `graph` of a join. `keyframes`: every keyframe of the join,
/// oldest first (the saved map's in its order, then the new run's), at the poses `graph`
/// solved; `new_ids`: the new run's keyframes, in order. A retired keyframe is folded out of
/// `graph` (PoseGraph::RemoveNode; a frozen saved keyframe into a frozen neighbour); the gauge
/// (SessionKeyframe::fixed) is never retired. Returns one anchor per retired keyframe, its hub
/// a keyframe still in `graph` or one retired after it (FollowRetiredHubs resolves those).
std::vector<SessionAnchor> RetireRevisitedViews(
    const std::vector<const SessionKeyframe*>& keyframes, const std::vector<int>& new_ids,
    const PlaceViewsConfig& config, PoseGraph* graph);

/// Every anchor whose hub is itself an anchor (a keyframe retired later) follows that anchor's
/// hub instead, composing the poses, until its hub is a kept keyframe (or -1: the map frame).
void FollowRetiredHubs(std::vector<SessionAnchor>* anchors);

}  // namespace uwbsar
