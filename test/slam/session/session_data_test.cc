// SessionData's queries: which runs a session holds, in which order.
#include "slam/session/session_data.h"

#include <gtest/gtest.h>

namespace uwbsar {
namespace {

SessionKeyframe KeyframeOf(int id, int trajectory) {
  SessionKeyframe k;
  k.id = id;
  k.trajectory = trajectory;
  return k;
}

TEST(SessionDataTest, RunsAreThoseWithKeyframesOrAnchorsInTheOrderTheyJoined) {
  SessionData s;
  for (int t : {0, 1, 2, 3}) s.trajectories.push_back({t, "run " + std::to_string(t), ""});
  s.keyframes = {KeyframeOf(0, 0), KeyframeOf(1, 0), KeyframeOf(7, 2)};
  EXPECT_EQ(s.TrajectoryIds(), (std::vector<int>{0, 2}));
  // Run 1's keyframes were all retired by run 2: its anchors still place it. Run 3 never joined
  // (no keyframe, no anchor): not a run of the map.
  SessionAnchor a;
  a.id = 4;
  a.trajectory = 1;
  a.hub_id = 7;
  s.anchors.push_back(a);
  EXPECT_EQ(s.TrajectoryIds(), (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(s.MaxKeyframeId(), 7);
}

}  // namespace
}  // namespace uwbsar
