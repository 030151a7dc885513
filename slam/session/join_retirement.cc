#include "slam/session/join_retirement.h"

#include <algorithm>
#include <map>
#include <set>

#include "core/errors.h"
#include "core/log.h"
#include "slam/session/place_views.h"

namespace uwbsar {

std::vector<SessionAnchor> RetireRevisitedViews(
    const std::vector<const SessionKeyframe*>& keyframes, const std::vector<int>& new_ids,
    const PlaceViewsConfig& config, PoseGraph* graph) {
  std::vector<SessionAnchor> retired;
  if (config.max_per_place <= 0 || new_ids.empty()) return retired;
  const std::set<int> tied = TiedByAcceptedLoops(graph->EdgeReports());
  const std::map<int, Pose2> poses = graph->GetPoses();
  std::vector<PlaceView> views;
  std::map<int, const SessionKeyframe*> by_id;
  for (std::size_t i = 0; i < keyframes.size(); ++i) {
    const SessionKeyframe& k = *keyframes[i];
    const Pose2& T_map_anchor = poses.at(k.id);
    PlaceView v;
    v.id = k.id;
    v.trajectory = k.trajectory;
    v.anchor_world = {T_map_anchor.x_m, T_map_anchor.y_m};
    // The anchor keeps its run's odometry orientation: the map turns the robot as the anchor.
    v.robot_heading_rad =
        NormalizeAngle(T_map_anchor.yaw_rad - k.T_odom_anchor.yaw_rad + k.T_odom_robot.yaw_rad);
    v.path_mid_m = 0.5 * (k.path_begin_m + k.path_end_m);
    v.stamp = static_cast<long long>(i);  // age: runs in the order they joined, then in time
    v.retirable = !k.fixed;
    views.push_back(v);
    by_id[k.id] = &k;
  }
  RetireRevisitedViews(&views, new_ids, tied, config, [&](int victim) {
    const SessionKeyframe& k = *by_id.at(victim);
    SessionAnchor a;
    a.id = k.id;
    a.trajectory = k.trajectory;
    a.stamp_ns = k.stamp_ns;
    a.T_odom_anchor = k.T_odom_anchor;
    try {
      a.hub_id = graph->RemoveNode(k.id, &a.T_hub_anchor);
    } catch (const InputError& e) {  // a frozen keyframe with no frozen neighbour left: kept
      Log(LogLevel::kDebug, std::string("view kept: ") + e.what());
      return false;
    }
    if (a.hub_id < 0) a.T_hub_anchor = poses.at(k.id);
    retired.push_back(a);
    return true;
  });
  return retired;
}

void FollowRetiredHubs(std::vector<SessionAnchor>* anchors) {
  std::map<int, std::size_t> index;
  for (std::size_t i = 0; i < anchors->size(); ++i) index[(*anchors)[i].id] = i;
  for (SessionAnchor& a : *anchors) {
    // Each hop goes to a keyframe retired later than the last: the chain ends.
    for (std::size_t hops = 0; hops <= anchors->size(); ++hops) {
      auto hub = index.find(a.hub_id);
      if (hub == index.end()) break;
      const SessionAnchor& h = (*anchors)[hub->second];
      a.T_hub_anchor = h.T_hub_anchor * a.T_hub_anchor;
      a.hub_id = h.hub_id;
    }
  }
}

}  // namespace uwbsar
