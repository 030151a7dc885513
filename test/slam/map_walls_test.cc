// A saved map's walls as a localised run sees them (slam/map_walls.h): a wall on one of the
// map's landmarks, where the map saw it, observes that landmark (its line facing the
// landmark's, whichever way the keyframe's fit turned it); a wall outside the gates, or far
// from every sighting, observes nothing.
#include "slam/map_walls.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace uwbsar::slam {
namespace {

constexpr double kPi = 3.14159265358979323846;
const Line2 kWall{kPi / 2, 7.0};  // the map's wall: y = 7 m

/// A map with one keyframe at (10, 5) that saw kWall 1 m ahead of its anchor.
SessionData OneWallMap() {
  SessionData map;
  SessionKeyframe k;
  k.id = 4;
  k.T_map_anchor = {10.0, 5.0, 0.3};
  map.keyframes.push_back(k);
  map.landmarks.push_back({0, kWall});
  SessionLineObservation o;
  o.observation.landmark_id = 0;
  o.observation.node_id = 4;
  o.observation.line_node = LineToFrame(k.T_map_anchor, kWall);
  o.observation.reference_node = {1.0, 0.0};
  map.line_observations.push_back(o);
  return map;
}

/// What a keyframe at T_map_anchor sees of the world line `wall`, `off_m` further from it; the
/// reference is the point of the seen line beside the anchor (as SeenLines makes it).
SeenLine Seen(const Pose2& T_map_anchor, const Line2& wall, double off_m) {
  SeenLine s;
  s.line_anchor = LineToFrame(T_map_anchor, wall);
  s.line_anchor.offset_m += off_m;
  const double nx = std::cos(s.line_anchor.normal_rad), ny = std::sin(s.line_anchor.normal_rad);
  s.reference_anchor = {s.line_anchor.offset_m * nx, s.line_anchor.offset_m * ny};
  s.offset_std_m = 0.03;
  s.normal_std_rad = 0.17;
  return s;
}

TEST(MapWallsTest, AWallOnTheMapsLandmarkObservesIt) {
  WallLineConfig gates;  // 10 cm, 3 deg
  const MapWalls walls(OneWallMap(), gates, 4.0);
  ASSERT_FALSE(walls.empty());
  EXPECT_EQ(walls.Line(0).offset_m, kWall.offset_m);
  const Pose2 T{12.5, 5.1, -0.05};
  const std::vector<LineObservation> seen = walls.Observe({Seen(T, kWall, 0.04)}, T, 17);
  ASSERT_EQ(seen.size(), 1u);
  EXPECT_EQ(seen[0].landmark_id, 0);
  EXPECT_EQ(seen[0].node_id, 17);
  EXPECT_NEAR(LineObservationChi2(seen[0], T, kWall), std::pow(0.04 / 0.03, 2), 1e-6);
  // The keyframe's fit may give the wall's normal the other way round: the observation faces
  // the landmark, so the graph sees the same line.
  SeenLine flipped = Seen(T, kWall, 0.04);
  flipped.line_anchor = {NormalizeAngle(flipped.line_anchor.normal_rad + kPi),
                         -flipped.line_anchor.offset_m};
  const std::vector<LineObservation> turned = walls.Observe({flipped}, T, 17);
  ASSERT_EQ(turned.size(), 1u);
  EXPECT_NEAR(NormalizeAngle(turned[0].line_node.normal_rad - seen[0].line_node.normal_rad), 0.0,
              1e-12);
  EXPECT_NEAR(turned[0].line_node.offset_m, seen[0].line_node.offset_m, 1e-12);
}

TEST(MapWallsTest, WallsOutsideTheGatesOrFarFromTheSightingsObserveNothing) {
  const WallLineConfig gates;
  const MapWalls walls(OneWallMap(), gates, 4.0);
  const Pose2 T{12.5, 5.1, -0.05};
  EXPECT_TRUE(walls.Observe({Seen(T, kWall, 0.15)}, T, 1).empty());  // 15 cm off its line
  // 5 deg off its angle, through the point of the map's wall beside the keyframe.
  const double a = kWall.normal_rad + 5.0 * kPi / 180;
  const Line2 turned{a, std::cos(a) * 12.5 + std::sin(a) * 7.0};
  EXPECT_TRUE(walls.Observe({Seen(T, turned, 0.0)}, T, 1).empty());
  const double b = kWall.normal_rad + 2.0 * kPi / 180;  // 2 deg: within the gate
  EXPECT_EQ(walls.Observe({Seen(T, {b, std::cos(b) * 12.5 + std::sin(b) * 7.0}, 0.0)}, T, 1).size(),
            1u);
  const Pose2 far{40.0, 5.0, 0.0};  // on the line, 30 m from where the map saw the wall
  EXPECT_TRUE(walls.Observe({Seen(far, kWall, 0.0)}, far, 1).empty());
  // Two walls near the landmark: the nearer one observes it, once.
  const std::vector<LineObservation> one =
      walls.Observe({Seen(T, kWall, 0.08), Seen(T, kWall, -0.02)}, T, 1);
  ASSERT_EQ(one.size(), 1u);
  EXPECT_NEAR(LineObservationChi2(one[0], T, kWall), std::pow(0.02 / 0.03, 2), 1e-6);
}

TEST(MapWallsTest, AMapWithoutWallsOrWithRejectedSightingsOnlyHasNone) {
  const WallLineConfig gates;
  EXPECT_TRUE(MapWalls().empty());
  EXPECT_TRUE(MapWalls(SessionData{}, gates, 4.0).empty());
  SessionData map = OneWallMap();
  map.line_observations[0].rejected = true;  // nobody saw it for sure: it cannot be met
  const MapWalls walls(map, gates, 4.0);
  EXPECT_TRUE(walls.empty());
  EXPECT_THROW(walls.Line(0), std::out_of_range);
}

}  // namespace
}  // namespace uwbsar::slam
