#include "session/session_data.h"

#include <algorithm>

#include "slam/slam_snapshot.h"

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

std::vector<std::pair<TimestampNs, Pose2>> SessionData::CorrectedTrajectory(int trajectory) const {
  std::vector<const SessionKeyframe*> run;
  for (const SessionKeyframe& k : keyframes) {
    if (k.trajectory == trajectory) run.push_back(&k);
  }
  std::stable_sort(run.begin(), run.end(), [](const SessionKeyframe* a, const SessionKeyframe* b) {
    return a->stamp_ns < b->stamp_ns;
  });
  std::vector<std::pair<TimestampNs, Pose2>> out;
  for (const SessionOdometry& o : odometry) {
    if (o.trajectory != trajectory) continue;
    const Pose2 correction = InterpolatedCorrection(
        run.size(), [&](std::size_t i) { return run[i]->stamp_ns; },
        [&](std::size_t i) -> const Pose2& { return run[i]->T_odom_anchor; },
        [&](std::size_t i) { return run[i]->T_map_anchor; }, o.stamp_ns);
    out.push_back({o.stamp_ns, correction * o.T_odom_robot});
  }
  return out;
}

}  // namespace uwbsar
