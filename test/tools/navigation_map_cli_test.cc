// map.pgm of `uwbsar demo` as a planner uses it (issue 29): the cells the robot swept are
// free, no free cell lies behind a wall of the simulated room, and A* with the robot's radius
// finds the route's farthest point without crossing a wall (test/navigation_checks.h).
#include <gtest/gtest.h>

#include <string>

#include "imaging/occupancy_grid.h"
#include "test/cli_runner.h"
#include "test/navigation_checks.h"
#include "test/tools/map_test_bag.h"

namespace uwbsar {
namespace {

TEST(NavigationMapCliTest, DemoMapIsFreeWhereTheRobotDroveAndPlannable) {
  const std::string dir = map_test::TempDir("navigation_demo");
  const testing::CliRun r = testing::Uwbsar("demo --out " + dir + "/demo");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const OccupancyGrid map = LoadOccupancyGrid(dir + "/demo/map.yaml");
  const OccupancyGrid truth =
      LoadOccupancyGrid(std::string(UWBSAR_SOURCE_DIR) + "/config/maps/seed_hall/seed_hall.yaml");
  testing::ExpectNavigationMap("demo", map, truth,
                               testing::ReadTumPoses(dir + "/demo/trajectory.tum"),
                               testing::ReadTumPoses(dir + "/demo/ground_truth.tum"));
}

}  // namespace
}  // namespace uwbsar
