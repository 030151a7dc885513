// The map of several runs (session.joined_mosaic): with "normalized_max" a run imaged
// brighter than another (other range, other heading) does not raise the occupancy
// threshold over the other run's walls, as the plain mean does.
#include "slam/outputs/session_mosaic.h"

#include <gtest/gtest.h>

#include "backend/global_map.h"

namespace uwbsar::tools {
namespace {

/// A 2 m x 1 m tile at (x0, 0) of run `trajectory`: background `level` / 10, a wall of
/// `level` along its middle row band (3 % of the pixels).
SessionKeyframe Tile(int id, int trajectory, double x0_m, float level) {
  SessionKeyframe k;
  k.id = id;
  k.trajectory = trajectory;
  k.detected_grid = ImageGrid::Covering(0.0, 2.0, 0.0, 1.0, 0.02);
  cv::Mat tile(k.detected_grid.rows, k.detected_grid.cols, CV_32FC1, cv::Scalar(level / 10));
  tile.rowRange(24, 26).setTo(level);
  k.detected = TileRef(tile);
  k.T_map_anchor = {x0_m, 0.0, 0.0};
  return k;
}

/// The occupancy of `session`'s `mosaic` under the slam.* occupancy rule.
OccupancyGrid Occupancy(const SessionData& session, JoinedMosaic mosaic) {
  Config config;
  config.session.joined_mosaic = mosaic;
  ImageGrid grid;
  cv::Mat observed;
  const cv::Mat map = slam::RenderSessionMosaic(session, config, &grid, &observed);
  return MapToOccupancy(map, observed, grid, config.slam.occupancy_resolution_m,
                        config.slam.occupied_fraction, config.slam.occupancy_reference_percentile);
}

/// Occupied cells of the occupancy rule (slam.* defaults) left of x = 2 m (run A's area).
int OccupiedInRunA(const SessionData& session, JoinedMosaic mosaic) {
  const OccupancyGrid occ = Occupancy(session, mosaic);
  int n = 0;
  for (int r = 0; r < occ.rows; ++r) {
    for (int c = 0; c < occ.cols; ++c) {
      const double x = occ.origin.x_m + (c + 0.5) * occ.resolution_m;
      n += x < 1.9 &&
           occ.cells[static_cast<std::size_t>(r) * occ.cols + c] == OccupancyGrid::kOccupied;
    }
  }
  return n;
}

TEST(SessionMosaicTest, ABrighterRunDoesNotHideTheOtherRunsWalls) {
  SessionData session;
  session.keyframes = {Tile(0, 0, 0.0, 1.0f), Tile(1, 1, 2.0, 10.0f)};  // B 10x brighter
  SessionData a_alone;
  a_alone.keyframes = {session.keyframes[0]};
  const int alone = OccupiedInRunA(a_alone, JoinedMosaic::kMean);
  ASSERT_GT(alone, 20);  // A's wall is occupied in A's own map
  EXPECT_EQ(OccupiedInRunA(session, JoinedMosaic::kMean),
            0);  // the joined mean: B's level sets the rule
  EXPECT_EQ(OccupiedInRunA(session, JoinedMosaic::kNormalizedMax), alone);
  EXPECT_EQ(OccupiedInRunA(session, JoinedMosaic::kNormalizedMean), alone);
}

/// A 2 m x 1 m tile at the origin of run `trajectory` whose pixels are `draw`n from `rng`.
template <typename Draw>
SessionKeyframe RandomTile(int id, int trajectory, cv::RNG* rng, Draw draw) {
  SessionKeyframe k = Tile(id, trajectory, 0.0, 1.0f);
  cv::Mat tile = k.detected.Load();  // in memory: drawn in place
  for (int r = 0; r < tile.rows; ++r) {
    for (int c = 0; c < tile.cols; ++c) tile.at<float>(r, c) = draw(rng);
  }
  return k;
}

TEST(SessionMosaicTest, NormalizedMaxKeepsEveryCellOccupiedInOneRunsOwnMap) {
  // Two runs over the same area: A's levels are even (uniform), B's have a long tail (a few
  // very bright pixels, as a corner reflector gives), so the runs' brightest 1 % differ.
  cv::RNG rng(7);
  SessionData session;
  session.keyframes = {
      RandomTile(0, 0, &rng, [](cv::RNG* g) { return static_cast<float>(g->uniform(0.0, 1.0)); }),
      RandomTile(1, 1, &rng, [](cv::RNG* g) {
        return static_cast<float>(1.0 / (1.001 - g->uniform(0.0, 1.0)));
      })};
  const OccupancyGrid joined = Occupancy(session, JoinedMosaic::kNormalizedMax);
  int checked = 0;
  for (int run = 0; run < 2; ++run) {
    SessionData alone;
    alone.keyframes = {session.keyframes[static_cast<std::size_t>(run)]};
    const OccupancyGrid own = Occupancy(alone, JoinedMosaic::kNormalizedMax);
    ASSERT_EQ(own.rows, joined.rows);  // the same area, on the same lattice
    ASSERT_EQ(own.cols, joined.cols);
    for (std::size_t i = 0; i < own.cells.size(); ++i) {
      if (own.cells[i] != OccupancyGrid::kOccupied) continue;
      ++checked;
      EXPECT_EQ(joined.cells[i], OccupancyGrid::kOccupied) << "run " << run << " cell " << i;
    }
  }
  EXPECT_GT(checked, 50);
}

}  // namespace
}  // namespace uwbsar::tools
