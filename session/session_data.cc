#include "session/session_data.h"

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
  return m;
}

int SessionData::MaxTrajectoryId() const {
  int m = -1;
  for (const SessionTrajectory& t : trajectories) m = std::max(m, t.id);
  for (const SessionKeyframe& k : keyframes) m = std::max(m, k.trajectory);
  return m;
}

std::map<int, Pose2> SessionData::Poses() const {
  std::map<int, Pose2> out;
  for (const SessionKeyframe& k : keyframes) out[k.id] = k.T_map_anchor;
  return out;
}

}  // namespace uwbsar
