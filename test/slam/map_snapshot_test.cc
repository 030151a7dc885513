// A live snapshot copies the SLAM state under the lock and writes it
// after releasing it. The copy must be complete and independent: the outputs written
// later from the copy, while SLAM has moved on, equal those written the old way (from the
// SlamSystem itself, lock held throughout) at the moment of the copy.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>

#include "backend/incremental_mosaic.h"
#include "drivers/sim/synthetic_run.h"
#include "slam/app_config.h"
#include "slam/outputs/map_outputs.h"

namespace uwbsar::tools {
namespace {

namespace fs = std::filesystem;

std::string Bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

/// summary.json without the process-wide peak memory (it may grow between the writes).
nlohmann::json SummaryWithoutMemory(const fs::path& dir) {
  nlohmann::json j = nlohmann::json::parse(Bytes(dir / "summary.json"));
  j.erase("peak_memory_mib");
  return j;
}

struct SimFeed {
  SyntheticRun run;
  std::size_t odom = 0, scan = 0;
  /// Feeds messages in time order until `until` scans were fed.
  void To(slam::SlamSystem& slam, std::size_t until) {
    while (scan < until && scan < run.scans.size()) {
      while (odom < run.odometry.size() &&
             run.odometry[odom].stamp_ns <= run.scans[scan].stamp_ns) {
        slam.AddOdometry(run.odometry[odom++]);
      }
      slam.AddScan(run.scans[scan++]);
    }
    if (until >= run.scans.size()) {
      while (odom < run.odometry.size()) slam.AddOdometry(run.odometry[odom++]);
    }
  }
};

/// A 1.5 m circle driven for 12 m (more than one lap: the second lap may close loops) past a
/// wall and a few posts.
SimFeed CircleRun(const Config& config) {
  SyntheticPath path;
  path.turn_radius_m = 1.5;
  path.length_m = 12.0;
  path.speed_mps = 0.5;
  std::vector<Scatterer> scene = WallScatterers({-3, -3}, {3, -3}, 0.02, 0.05);
  for (int i = 0; i < 12; ++i) scene.push_back({{-2.5 + 0.45 * i, i % 2 ? 2.6 : -0.3}, 1.0});
  return SimFeed{SimulateRun(config, path, scene, EchoModel{}, 5)};
}

TEST(MapSnapshotTest, OutputsFromTheCopyEqualThoseWrittenUnderTheLockAtThatMoment) {
  Config config;
  config.slam.keyframe_thread = true;
  SimFeed feed = CircleRun(config);

  slam::MapRun run;
  run.input = "synthetic circle";
  run.slam = std::make_shared<slam::SlamSystem>(config);
  feed.To(*run.slam, feed.run.scans.size() / 2);
  run.slam->WaitIdle();

  const fs::path dir = fs::temp_directory_path() / "uwbsar_map_snapshot_test";
  fs::remove_all(dir);
  slam::MapState state;
  {
    const auto lock = run.slam->LockState();
    ASSERT_GE(run.slam->keyframes().size(), 3u);
    state = slam::CaptureMapState(run);
    slam::WriteMapOutputs(run,
                          (dir / "old_way").string());  // the old snapshot: all under the lock
  }
  // SLAM moves on: more keyframes, new solves, more odometry.
  feed.To(*run.slam, feed.run.scans.size());
  run.slam->Finish();
  ASSERT_GT(run.slam->keyframes().size(), state.slam.tiles.size());
  slam::WriteMapOutputs(state, (dir / "copy").string());
  slam::WriteMapOutputs(run, (dir / "final").string());

  for (const char* f : {"trajectory.tum", "odometry.tum", "graph.g2o", "loops.csv", "map_float.tif",
                        "map_grid.yaml", "map.png", "map.pgm", "map.yaml"}) {
    const std::string old_way = Bytes(dir / "old_way" / f);
    EXPECT_FALSE(old_way.empty()) << f;
    EXPECT_TRUE(old_way == Bytes(dir / "copy" / f)) << f << ": the copy's output differs";
  }
  EXPECT_EQ(SummaryWithoutMemory(dir / "old_way"), SummaryWithoutMemory(dir / "copy"));
  // The test can fail: the final state wrote different files.
  EXPECT_FALSE(Bytes(dir / "old_way" / "odometry.tum") == Bytes(dir / "final" / "odometry.tum"));
  EXPECT_NE(SummaryWithoutMemory(dir / "old_way"), SummaryWithoutMemory(dir / "final"));
}

/// A live run keeps its map between snapshots (MapOutputStage::KeepMosaic) and redraws only
/// what changed: the map it writes at the end equals one rendered from every tile.
TEST(MapSnapshotTest, AKeptMosaicEqualsAFullRenderOfTheSameState) {
  Config config;
  config.slam.keyframe_thread = false;
  config.slam.mosaic_redraw_px = 0.0;  // exact: every moved keyframe is redrawn
  SimFeed feed = CircleRun(config);
  slam::MapRun run;
  run.input = "synthetic circle";
  run.slam = std::make_shared<slam::SlamSystem>(config);

  const fs::path dir = fs::temp_directory_path() / "uwbsar_map_snapshot_kept_mosaic";
  fs::remove_all(dir);
  IncrementalMosaic mosaic(config.slam.map_resolution_m, config.slam.mosaic_redraw_px);
  std::size_t keyframes_at_first = 0;
  for (std::size_t part = 1; part <= 3; ++part) {
    feed.To(*run.slam, feed.run.scans.size() * part / 3);
    if (part == 3) run.slam->Finish();
    slam::MapState state;
    {
      const auto lock = run.slam->LockState();
      state = slam::CaptureMapState(run);
    }
    if (part == 1) keyframes_at_first = state.slam.tiles.size();
    slam::MapOutputStage stage((dir / "kept").string());
    stage.KeepMosaic(&mosaic);
    stage.Commit(state);
  }
  ASSERT_GE(keyframes_at_first, 2u);
  ASSERT_GT(run.slam->keyframes().size(), keyframes_at_first);
  slam::WriteMapOutputs(run, (dir / "full").string());
  const cv::Mat kept = cv::imread((dir / "kept" / "map_float.tif").string(), cv::IMREAD_UNCHANGED);
  const cv::Mat full = cv::imread((dir / "full" / "map_float.tif").string(), cv::IMREAD_UNCHANGED);
  ASSERT_FALSE(full.empty());
  ASSERT_EQ(kept.size(), full.size());
  double full_max = 0.0;
  cv::minMaxLoc(full, nullptr, &full_max);
  EXPECT_GT(full_max, 0.0);
  EXPECT_LT(cv::norm(kept, full, cv::NORM_INF), 1e-4 * full_max);
  EXPECT_EQ(Bytes(dir / "kept" / "map_grid.yaml"), Bytes(dir / "full" / "map_grid.yaml"));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace uwbsar::tools
