// map.pgm of `uwbsar demo` as a planner uses it (issue 29): the cells the robot swept are
// free, no free cell lies behind a wall of the simulated room, and A* with the robot's radius
// finds the route's farthest point without crossing a wall (test/navigation_checks.h); the /map
// of localize's results.mcap is that file.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "drivers/rosbag/bag_storage.h"
#include "imaging/occupancy_grid.h"
#include "test/cli_runner.h"
#include "test/navigation_checks.h"
#include "test/tools/map_test_bag.h"

namespace uwbsar {
namespace {

/// The last `n` cells of the first /map of `mcap` (nav_msgs/OccupancyGrid: its data, the
/// message's last bytes after their uint32 count, bottom row first); empty when there is no
/// /map or its data is not `n` cells.
std::vector<std::int8_t> FirstMapCells(const std::string& mcap, std::size_t n) {
  auto reader = rosbag::OpenMcapStorage(mcap);
  rosbag::StorageMessage msg;
  while (reader->Next(&msg)) {
    if (reader->Topics()[static_cast<std::size_t>(msg.topic)].name != "/map") continue;
    std::uint32_t count = 0;
    if (msg.size < n + 4) return {};
    std::memcpy(&count, msg.data + msg.size - n - 4, 4);
    if (count != n) return {};
    return {msg.data + msg.size - n, msg.data + msg.size};
  }
  return {};
}

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

// Issue 45 item 13: localize's /map, documented as the saved map's grid, was made again from
// the session, whose tiles are stored in 1023 levels and whose odometry is thinned: it differed
// from map.pgm in 84 of 30,192 cells. It is the map folder's map.pgm, cell for cell.
TEST(NavigationMapCliTest, LocalizeResultsMapIsTheSavedMapPgmCellForCell) {
  const std::string dir = map_test::TempDir("navigation_localize");
  const std::string bag = map_test::WriteRunBag(dir, {});
  testing::CliRun r = testing::Uwbsar("map " + bag + " --out " + dir + "/map");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = testing::Uwbsar("localize " + bag + " --map " + dir + "/map --out " + dir + "/loc");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::vector<std::int8_t> saved =
      GridCellsBottomUp(LoadOccupancyGrid(dir + "/map/map.yaml"));
  const std::vector<std::int8_t> published = FirstMapCells(dir + "/loc/results.mcap", saved.size());
  ASSERT_EQ(published.size(), saved.size()) << "/map is not map.pgm's size";
  std::size_t differ = 0;
  for (std::size_t i = 0; i < saved.size(); ++i) differ += published[i] != saved[i];
  EXPECT_EQ(differ, 0u) << "of " << saved.size() << " cells";
}

}  // namespace
}  // namespace uwbsar
