// The wall landmark tracker (slam/wall_landmarks.h): the walls keyframes see along a corridor
// become one track per wall, entering the graph once min_observations keyframes saw them; a
// turn or a gap longer than max_gap ends a track, and a line measured with its normal turned
// over still joins its wall.
#include "slam/wall_landmarks.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>

namespace uwbsar::slam {
namespace {

constexpr double kPi = 3.14159265358979323846;

/// The walls y = 1 and y = -1.25 (world) seen from an anchor at `T_world_anchor`, 1 m ahead.
std::vector<SeenLine> CorridorWalls(const Pose2& T_world_anchor, bool turn_left_normal = false) {
  std::vector<SeenLine> lines;
  for (const Line2& wall : {Line2{kPi / 2, 1.0}, Line2{-kPi / 2, 1.25}}) {
    SeenLine s;
    s.line_anchor = LineToFrame(T_world_anchor, wall);
    if (turn_left_normal && wall.offset_m == 1.0) {
      s.line_anchor = {NormalizeAngle(s.line_anchor.normal_rad + kPi), -s.line_anchor.offset_m};
    }
    s.reference_anchor = {1.0, 0.0};
    lines.push_back(s);
  }
  return lines;
}

/// Anchors 1 m apart along +x with the odometry's heading drift (0.003 rad/m): in the
/// odometry's frame the walls bend away, by 0.6 m and 3.4 degrees after 20 m.
Pose2 Anchor(int k) {
  Pose2 p;
  for (int i = 0; i < k; ++i) p = p * Pose2{1.0, 0.0, 0.003};
  return p;
}

TEST(WallLandmarkTrackerTest, ACorridorsTwoWallsBecomeTwoLandmarksSeenByEveryKeyframe) {
  WallProfileConfig profiles;
  const WallLineConfig& config = profiles.landmarks;
  WallLandmarkTracker tracker(profiles, 5);
  std::map<int, int> observations;  // by landmark
  std::vector<int> entered_at;
  for (int k = 0; k < 20; ++k) {
    // The walls as the truth has them, seen from the true anchor (the tracker gets the
    // odometry's pose, which drifts away from it slowly).
    const Pose2 truth{static_cast<double>(k), 0.0, 0.0};
    const WallLandmarkTracker::Update u = tracker.Add(100 + k, Anchor(k), CorridorWalls(truth));
    for (const auto& [id, line] : u.new_landmarks) {
      entered_at.push_back(k);
      EXPECT_GE(id, 5);
    }
    for (const LineObservation& o : u.observations) {
      ++observations[o.landmark_id];
      EXPECT_LE(o.node_id, 100 + k);
    }
  }
  EXPECT_EQ(tracker.tracks_started(), 2);
  EXPECT_EQ(entered_at,
            (std::vector<int>{config.min_observations - 1, config.min_observations - 1}));
  ASSERT_EQ(observations.size(), 2u);
  EXPECT_EQ(observations.at(5), 20);
  EXPECT_EQ(observations.at(6), 20);
  EXPECT_EQ(tracker.next_landmark_id(), 7);
}

TEST(WallLandmarkTrackerTest, ATurnOrAGapEndsATrack) {
  WallProfileConfig profiles;
  profiles.landmarks.max_gap = 2;
  WallLandmarkTracker tracker(profiles);
  for (int k = 0; k < 4; ++k)
    tracker.Add(k, Pose2{1.0 * k, 0.0, 0.0}, CorridorWalls({1.0 * k, 0.0, 0.0}));
  EXPECT_EQ(tracker.tracks_started(), 2);
  // Two keyframes without walls (a doorway, an open hall) still keep the tracks.
  tracker.Add(4, Pose2{4.0, 0.0, 0.0}, {});
  tracker.Add(5, Pose2{5.0, 0.0, 0.0}, {});
  tracker.Add(6, Pose2{6.0, 0.0, 0.0}, CorridorWalls({6.0, 0.0, 0.0}));
  EXPECT_EQ(tracker.tracks_started(), 2);
  // Three do not.
  for (int k = 7; k < 10; ++k) tracker.Add(k, Pose2{1.0 * k, 0.0, 0.0}, {});
  tracker.Add(10, Pose2{10.0, 0.0, 0.0}, CorridorWalls({10.0, 0.0, 0.0}));
  EXPECT_EQ(tracker.tracks_started(), 4);
  // Around a corner the walls are other walls: x = 11 and x = 8.75, along the new heading.
  const Pose2 turned{10.0, 0.0, kPi / 2};
  std::vector<SeenLine> around(2);
  around[0].line_anchor = LineToFrame(turned, {0.0, 11.0});
  around[1].line_anchor = LineToFrame(turned, {kPi, -8.75});
  tracker.Add(11, turned, around);
  EXPECT_EQ(tracker.tracks_started(), 6);
}

TEST(WallLandmarkTrackerTest, ALineWithItsNormalTurnedOverJoinsItsWallAndFacesIt) {
  WallLandmarkTracker tracker{WallProfileConfig()};
  std::vector<LineObservation> all;
  for (int k = 0; k < 6; ++k) {
    const Pose2 p{1.0 * k, 0.0, 0.0};
    const WallLandmarkTracker::Update u = tracker.Add(k, p, CorridorWalls(p, k % 2 == 1));
    all.insert(all.end(), u.observations.begin(), u.observations.end());
  }
  EXPECT_EQ(tracker.tracks_started(), 2);
  ASSERT_EQ(all.size(), 12u);
  for (const LineObservation& o : all) {
    // Every observation of the left wall has its normal pointing left, as the first one.
    if (o.landmark_id == 0) {
      EXPECT_NEAR(o.line_node.normal_rad, kPi / 2, 1e-9) << o.node_id;
      EXPECT_NEAR(o.line_node.offset_m, 1.0, 1e-9) << o.node_id;
    }
  }
}

}  // namespace
}  // namespace uwbsar::slam
