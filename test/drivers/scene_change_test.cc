// A changing world: a day-2 building drawn from a change seed (objects added, removed, moved;
// doors closed and opened) and people walking past during a run.
#include "drivers/sim/scene_change.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <vector>

#include "app/app_config.h"
#include "drivers/sim/laser_simulator.h"
#include "drivers/sim/sim_stream.h"
#include "drivers/sim/walking_people.h"
#include "test/drivers/sim_test_util.h"

namespace uwbsar::sim {
namespace {

using Kind = SceneEdit::Kind;
using testing::FreeGrid;
using testing::Occupy;
using testing::WallAlongX;

std::string RepoFile(const std::string& relative) {
  return (std::filesystem::path(UWBSAR_SOURCE_DIR) / relative).string();
}

void Square(OccupancyGrid* g, double cx, double cy, double side) {
  for (double x = cx - side / 2 + 0.01; x < cx + side / 2; x += 0.05) {
    for (double y = cy - side / 2 + 0.01; y < cy + side / 2; y += 0.05) Occupy(g, {x, y});
  }
}

// 8 m x 6 m: the route along y = 2.5; a wall (two cells thick) along y = 4.5 with a 0.9 m
// doorway at x = 3.0 .. 3.9 and a room behind it; three 0.3 m objects near the route.
struct HandWorld {
  OccupancyGrid grid = FreeGrid(120, 160, 0.05, 0.0, 0.0);
  std::vector<Point2> route{{1.0, 2.5}, {7.0, 2.5}};
  std::vector<int> doorway;

  HandWorld() {
    for (double y : {4.47, 4.52}) {
      WallAlongX(&grid, y, 0.0, 2.99);
      WallAlongX(&grid, y, 3.91, 7.99);
      for (double x = 3.025; x < 3.9; x += 0.05) {
        int row = 0, col = 0;
        grid.CellOf({x, y}, &row, &col);
        doorway.push_back(row * grid.cols + col);
      }
    }
    Square(&grid, 2.0, 1.2, 0.3);
    Square(&grid, 5.0, 1.2, 0.3);
    Square(&grid, 6.0, 3.6, 0.3);
  }
};

SimSceneChangeConfig OneOfEach() {
  SimSceneChangeConfig c;
  c.seed = 11;
  c.objects_added = 3;
  c.objects_removed = 1;
  c.objects_moved = 1;
  c.doors_closed = 1;
  c.doors_opened = 1;
  return c;
}

std::set<int> EditedCells(const SceneChange& change) {
  std::set<int> cells;
  for (const SceneEdit& e : change.edits) {
    cells.insert(e.occupied.begin(), e.occupied.end());
    cells.insert(e.freed.begin(), e.freed.end());
  }
  return cells;
}

std::vector<int> ChangedCells(const OccupancyGrid& a, const OccupancyGrid& b) {
  std::vector<int> cells;
  for (int i = 0; i < static_cast<int>(a.cells.size()); ++i) {
    if (a.IsOccupied(i / a.cols, i % a.cols) != b.IsOccupied(i / b.cols, i % b.cols)) {
      cells.push_back(i);
    }
  }
  return cells;
}

bool SameScatterers(const SimEnvironment& a, const SimEnvironment& b, int cell) {
  if (a.CellEnd(cell) - a.CellBegin(cell) != b.CellEnd(cell) - b.CellBegin(cell)) return false;
  for (int i = a.CellBegin(cell), j = b.CellBegin(cell); i < a.CellEnd(cell); ++i, ++j) {
    const SimScatterer &s = a.scatterers()[i], &t = b.scatterers()[j];
    if (s.x_m != t.x_m || s.y_m != t.y_m || s.in_phase != t.in_phase ||
        s.quadrature != t.quadrature) {
      return false;
    }
  }
  return true;
}

// The point of the polyline `route` nearest to `p`.
Point2 NearestOnRoute(const Point2& p, const std::vector<Point2>& route) {
  Point2 best = route[0];
  for (std::size_t i = 0; i + 1 < route.size(); ++i) {
    const Point2 &a = route[i], &b = route[i + 1];
    const double dx = b.x_m - a.x_m, dy = b.y_m - a.y_m;
    const double t = std::clamp(
        ((p.x_m - a.x_m) * dx + (p.y_m - a.y_m) * dy) / std::max(dx * dx + dy * dy, 1e-12), 0.0,
        1.0);
    const Point2 q{a.x_m + t * dx, a.y_m + t * dy};
    if (std::hypot(q.x_m - p.x_m, q.y_m - p.y_m) < std::hypot(best.x_m - p.x_m, best.y_m - p.y_m)) {
      best = q;
    }
  }
  return best;
}

TEST(SceneChangeTest, EditsTheBuildingOnlyWhereItsEditsAreAndTheEchoesFollow) {
  const HandWorld world;
  const SceneChange change = DrawSceneChange(world.grid, world.route, OneOfEach(), 11);
  EXPECT_EQ(change.Count(Kind::kObjectAdded), 3);
  EXPECT_EQ(change.Count(Kind::kObjectRemoved), 1);
  EXPECT_EQ(change.Count(Kind::kObjectMoved), 1);
  ASSERT_EQ(change.Count(Kind::kDoorClosed), 1);
  EXPECT_EQ(change.Count(Kind::kDoorOpened), 1);
  const std::set<int> edited = EditedCells(change);
  const std::vector<int> changed = ChangedCells(world.grid, change.grid);
  EXPECT_EQ(std::set<int>(changed.begin(), changed.end()), edited);
  for (const SceneEdit& e : change.edits) {
    if (e.kind == Kind::kDoorClosed) {  // the doorway, filled across the wall
      EXPECT_EQ(std::set<int>(e.occupied.begin(), e.occupied.end()),
                std::set<int>(world.doorway.begin(), world.doorway.end()));
    }
    if (e.kind == Kind::kDoorOpened) {  // 0.9 m of the wall, both rows
      EXPECT_EQ(e.freed.size(), 36u);
      EXPECT_NEAR(e.where.y_m, 4.5, 0.05);
    }
    if (e.kind == Kind::kObjectAdded) {  // 15 - 25 cm, 0.7 - 1.3 m beside the route
      EXPECT_GE(e.occupied.size(), 9u);
      EXPECT_LE(e.occupied.size(), 25u);
      EXPECT_GE(std::abs(e.where.y_m - 2.5), 0.7 - 0.03);
      EXPECT_LE(std::abs(e.where.y_m - 2.5), 1.3 + 0.03);
    }
    if (e.kind == Kind::kObjectMoved) {
      EXPECT_EQ(e.occupied.size(), e.freed.size());
    }
  }
  // The radars' scatterers: the day-1 ones wherever no edit is, new ones where objects came.
  SimRadarConfig radar;
  const SimEnvironment day1(world.grid, radar, 7);
  const SimEnvironment day2(world.grid, radar, 7, &change.grid);
  int differing = 0;
  for (int cell = 0; cell < static_cast<int>(world.grid.cells.size()); ++cell) {
    const bool same = SameScatterers(day1, day2, cell);
    differing += !same;
    EXPECT_EQ(same, edited.count(cell) == 0) << "cell " << cell;
    const int count = day2.CellEnd(cell) - day2.CellBegin(cell);
    EXPECT_EQ(count, change.grid.IsOccupied(cell / 160, cell % 160) ? 4 : 0);
  }
  EXPECT_EQ(differing, static_cast<int>(edited.size()));
}

TEST(SceneChangeTest, TheSameSeedGivesTheSameChangeAndAnotherSeedAnother) {
  const HandWorld world;
  const SceneChange a = DrawSceneChange(world.grid, world.route, OneOfEach(), 11);
  const SceneChange b = DrawSceneChange(world.grid, world.route, OneOfEach(), 11);
  const SceneChange c = DrawSceneChange(world.grid, world.route, OneOfEach(), 12);
  EXPECT_EQ(a.grid.cells, b.grid.cells);
  ASSERT_EQ(a.edits.size(), b.edits.size());
  for (std::size_t i = 0; i < a.edits.size(); ++i) {
    EXPECT_EQ(a.edits[i].occupied, b.edits[i].occupied);
    EXPECT_EQ(a.edits[i].freed, b.edits[i].freed);
  }
  EXPECT_NE(a.grid.cells, c.grid.cells);
}

TEST(SceneChangeTest, TheDefaultsKeepTheMapsBuildingAndItsScatterers) {
  const Config config;
  EXPECT_FALSE(config.simulator.scene_change.seed.has_value());
  EXPECT_EQ(config.simulator.people.count, 0);
  const std::string map = RepoFile("config/maps/seed_hall/seed_hall.yaml");
  const SimScenario scenario = MakeScenario(config, map, "depart-return", 1);
  EXPECT_TRUE(scenario.scene_edits.empty());
  const OccupancyGrid grid = LoadOccupancyGrid(map);
  EXPECT_EQ(scenario.environment->grid().cells, grid.cells);
  // A "change" to the same building keeps every scatterer.
  const SimEnvironment unchanged(grid, config.simulator.radar, 1, &grid);
  for (int cell = 0; cell < static_cast<int>(grid.cells.size()); ++cell) {
    ASSERT_TRUE(SameScatterers(*scenario.environment, unchanged, cell)) << cell;
  }
}

TEST(SceneChangeTest, ATourChangesBesideTheRouteAndTheLidarSeesTheChangedBuilding) {
  Config config;
  config.simulator.scene_change.seed = 3;
  const std::string map = RepoFile("config/maps/tours/office_block.yaml");
  const std::string route = RepoFile("config/maps/tours/office_block_tour.txt");
  const SimScenario day2 = MakeScenario(config, map, route, 1);
  SceneChange summary;
  summary.edits = day2.scene_edits;
  EXPECT_EQ(summary.Count(Kind::kObjectAdded), 6);
  EXPECT_EQ(summary.Count(Kind::kObjectRemoved), 2);
  EXPECT_EQ(summary.Count(Kind::kObjectMoved), 2);
  EXPECT_EQ(summary.Count(Kind::kDoorClosed), 1);
  EXPECT_EQ(summary.Count(Kind::kDoorOpened), 1);
  const OccupancyGrid day1 = LoadOccupancyGrid(map);
  const std::vector<int> changed = ChangedCells(day1, day2.environment->grid());
  EXPECT_EQ(std::set<int>(changed.begin(), changed.end()), EditedCells(summary));
  // A LiDAR on the route beside an added object: the beams towards it stop there, earlier
  // than on day 1.
  const SceneEdit& added =
      *std::find_if(day2.scene_edits.begin(), day2.scene_edits.end(),
                    [](const SceneEdit& e) { return e.kind == Kind::kObjectAdded; });
  const Point2 on_route = NearestOnRoute(added.where, day2.route.waypoints);
  const double distance =
      std::hypot(added.where.x_m - on_route.x_m, added.where.y_m - on_route.y_m);
  EXPECT_GE(distance, 0.7 - 0.03);
  EXPECT_LE(distance, 1.3 + 0.03);
  const double towards = std::atan2(added.where.y_m - on_route.y_m, added.where.x_m - on_route.x_m);
  const GridRayCaster before(day1), after(day2.environment->grid());
  const Pose2 laser{on_route.x_m, on_route.y_m, towards};
  const SimLaserConfig lidar;  // 360 beams, beam 180 straight ahead
  const SimLaserScan a = SimulateLaserScan(before, laser, lidar, nullptr);
  const SimLaserScan b = SimulateLaserScan(after, laser, lidar, nullptr);
  for (int i = 178; i <= 182; ++i) {
    EXPECT_LT(b.ranges_m[i], a.ranges_m[i]) << i;
    EXPECT_NEAR(b.ranges_m[i], distance, 0.2) << i;
  }
}

TEST(WalkingPeopleTest, APersonWalksBesideTheRouteAndTheLidarSeesIt) {
  const HandWorld world;
  SimPeopleConfig config;
  config.count = 2;
  config.walk_length_m = 3.0;
  const std::vector<WalkingPerson> people = PlaceWalkingPeople(world.grid, world.route, config, 5);
  ASSERT_EQ(people.size(), 2u);
  for (const WalkingPerson& p : people) {
    EXPECT_LE(std::abs(p.from.y_m - 2.5), 1.0 + 1e-9);  // beside the route, parallel to it
    EXPECT_GE(std::abs(p.from.y_m - 2.5), 0.4 - 1e-9);
    EXPECT_NEAR(p.to.y_m, p.from.y_m, 1e-9);
    const double length = std::hypot(p.to.x_m - p.from.x_m, p.to.y_m - p.from.y_m);
    EXPECT_LE(length, 3.0 + 1e-6);
    EXPECT_GE(length, 1.0);
    // Walking at 1 m/s along its path (to and fro: never farther than it walked).
    const SimDisc a = p.At(10.0), b = p.At(10.5);
    EXPECT_LE(std::hypot(b.x_m - a.x_m, b.y_m - a.y_m), 0.5 + 1e-9);
    EXPECT_NEAR(b.y_m, p.from.y_m, 1e-9);
  }
  const SimDisc d = people[0].At(2.0);
  EXPECT_EQ(PlaceWalkingPeople(world.grid, world.route, config, 5)[0].At(2.0).x_m, d.x_m);
  // A LiDAR 2 m in front of the person measures 2 m less its radius.
  const GridRayCaster caster(world.grid);
  SimLaserConfig lidar;
  lidar.num_beams = 360;
  const Pose2 at{d.x_m - 2.0, d.y_m, 0.0};
  const SimLaserScan scan = SimulateLaserScan(caster, at, lidar, nullptr, {d});
  EXPECT_NEAR(scan.ranges_m[180], 2.0 - 0.2, 1e-4);  // beam 180: straight ahead
}

TEST(WalkingPeopleTest, APersonsEchoMovesBetweenScans) {
  Config config;
  config.simulator.route.depart_distance_m = 2.0;
  config.simulator.route.speed_mps = 0.5;
  config.simulator.route.pause_s = 0.2;
  config.simulator.radar.rate_hz = 10.0;
  config.simulator.people.offset_m = 0.8;
  config.simulator.people.walk_length_m = 3.0;
  const std::string map = RepoFile("config/maps/seed_hall/seed_hall.yaml");
  const SimScenario scenario = MakeScenario(config, map, "depart-return", 1);
  Config with_people = config;
  with_people.simulator.people.count = 1;
  SimStream quiet(config, scenario, 4), busy(with_people, scenario, 4);
  SimMessage a, b;
  std::vector<int> peaks;  // the strongest difference's bin, scan by scan (radar 0)
  while (quiet.Next(&a) && busy.Next(&b)) {
    ASSERT_EQ(a.kind, b.kind);
    if (a.kind != SimMessage::Kind::kRadarScan || a.scan.sensor_id != 0) continue;
    int best = 0;
    float peak = 0.0f;
    for (std::size_t k = 0; k < a.scan.samples.size(); ++k) {
      const float diff = std::abs(b.scan.samples[k] - a.scan.samples[k]);
      if (diff > peak) peak = diff, best = static_cast<int>(k);
    }
    if (peak > 1e-3f) peaks.push_back(best);
  }
  ASSERT_GE(peaks.size(), 5u);
  const auto [lo, hi] = std::minmax_element(peaks.begin(), peaks.end());
  EXPECT_GE(*hi - *lo, 20) << "the echo stayed at one range";
}

}  // namespace
}  // namespace uwbsar::sim
