#include "slam/session/session_data.h"

#include <algorithm>

namespace uwbsar {

const SessionKeyframe* SessionData::Find(int id) const {
  for (const SessionKeyframe& k : keyframes) {
    if (k.id == id) return &k;
  }
  return nullptr;
}

int SessionData::MaxKeyframeId() const {
  int m = -1;
  for (const SessionKeyframe& k : keyframes) m = std::max(m, k.id);
  for (const SessionAnchor& a : anchors) m = std::max(m, a.id);
  return m;
}

std::optional<Pose2> SessionAnchor::MapPose(const std::map<int, Pose2>& poses) const {
  if (hub_id < 0) return T_hub_anchor;
  const auto it = poses.find(hub_id);
  if (it == poses.end()) return std::nullopt;
  return it->second * T_hub_anchor;
}

int SessionData::MaxTrajectoryId() const {
  int m = -1;
  for (const SessionTrajectory& t : trajectories) m = std::max(m, t.id);
  for (const SessionKeyframe& k : keyframes) m = std::max(m, k.trajectory);
  return m;
}

int SessionData::MaxLandmarkId() const {
  int m = -1;
  for (const SessionLandmark& l : landmarks) m = std::max(m, l.id);
  return m;
}

std::vector<int> SessionData::TrajectoryIds() const {
  std::vector<int> ids;
  for (const SessionKeyframe& k : keyframes) {
    if (std::find(ids.begin(), ids.end(), k.trajectory) == ids.end()) ids.push_back(k.trajectory);
  }
  // A run whose every keyframe a later run retired is still placed, by its anchors: it takes
  // its place in the order the runs joined.
  std::vector<int> anchored;
  for (const SessionAnchor& a : anchors) {
    const bool known = std::find(ids.begin(), ids.end(), a.trajectory) != ids.end() ||
                       std::find(anchored.begin(), anchored.end(), a.trajectory) != anchored.end();
    if (!known) anchored.push_back(a.trajectory);
  }
  if (anchored.empty()) return ids;
  std::vector<int> ordered;
  for (const SessionTrajectory& t : trajectories) {
    const bool placed = std::find(ids.begin(), ids.end(), t.id) != ids.end() ||
                        std::find(anchored.begin(), anchored.end(), t.id) != anchored.end();
    if (placed && std::find(ordered.begin(), ordered.end(), t.id) == ordered.end())
      ordered.push_back(t.id);
  }
  for (const int id : ids) {  // keyframes of a run the trajectories table does not list
    if (std::find(ordered.begin(), ordered.end(), id) == ordered.end()) ordered.push_back(id);
  }
  return ordered;
}

std::map<int, Pose2> SessionData::Poses() const {
  std::map<int, Pose2> out;
  for (const SessionKeyframe& k : keyframes) out[k.id] = k.T_map_anchor;
  return out;
}

SessionData WithDenseIds(const SessionData& s) {
  SessionData out = s;
  std::map<int, int> keyframe, trajectory;
  for (SessionTrajectory& t : out.trajectories) {
    const int id = static_cast<int>(trajectory.size());
    trajectory.emplace(t.id, id);
    t.id = id;
  }
  const auto trajectory_of = [&](int id) {
    const auto it = trajectory.find(id);
    if (it != trajectory.end()) return it->second;
    const int dense = static_cast<int>(trajectory.size());
    return trajectory[id] = dense;
  };
  for (SessionKeyframe& k : out.keyframes) {
    const int id = static_cast<int>(keyframe.size());
    keyframe.emplace(k.id, id);
    k.id = k.features.id = id;
    k.trajectory = trajectory_of(k.trajectory);
  }
  // References to keyframes the session lacks (never in a session that was read) keep theirs.
  const auto keyframe_of = [&](int id) {
    const auto it = keyframe.find(id);
    return it != keyframe.end() ? it->second : id;
  };
  for (SessionEdge& e : out.edges) {
    e.edge.from_id = keyframe_of(e.edge.from_id);
    e.edge.to_id = keyframe_of(e.edge.to_id);
    if (e.edge.trajectory >= 0) e.edge.trajectory = trajectory_of(e.edge.trajectory);
  }
  for (SessionLoop& l : out.loops) {
    l.query_id = keyframe_of(l.query_id);
    l.match_id = keyframe_of(l.match_id);
  }
  for (SessionOdometry& o : out.odometry) o.trajectory = trajectory_of(o.trajectory);
  int next = static_cast<int>(keyframe.size());  // anchors after the keyframes
  for (SessionAnchor& a : out.anchors) {
    a.id = next++;
    if (a.hub_id >= 0) a.hub_id = keyframe_of(a.hub_id);
    a.trajectory = trajectory_of(a.trajectory);
  }
  std::map<int, int> landmark;
  for (SessionLandmark& l : out.landmarks) {
    const int id = static_cast<int>(landmark.size());
    landmark.emplace(l.id, id);
    l.id = id;
  }
  for (SessionLineObservation& o : out.line_observations) {
    o.observation.node_id = keyframe_of(o.observation.node_id);
    const auto it = landmark.find(o.observation.landmark_id);
    if (it != landmark.end()) o.observation.landmark_id = it->second;
  }
  return out;
}

}  // namespace uwbsar
