// The live runner on a shortened emulated run: what it records, maps offline to the
// same trajectory it produced live; it measures latency and writes its outputs.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "live_test_util.h"
#include "test/shared_data.h"

namespace uwbsar::live {
namespace {

TEST(LiveRunTest, RecordingMappedOfflineReproducesTheLiveTrajectory) {
  UWBSAR_NEED_SEED_LAB_MAP();
  Config config;
  config.live.snapshot_period_s = 2.0;
  const EmulatedRun live = RunEmulated(config, "short", 2.0, 14.0);
  const tools::LiveRunResult& r = live.result;
  ASSERT_TRUE(r.run.slam);
  ASSERT_FALSE(r.run.slam->keyframes().empty());
  EXPECT_EQ(r.dropped_from_processing, 0);
  EXPECT_GT(r.scans_received, 2000);
  // Every scan and odometry sample is recorded (plus GPIO / fault / run events).
  EXPECT_GE(r.recorded_messages, r.scans_received + r.odometry_received);
  EXPECT_GT(r.latency_samples, 2000);
  EXPECT_GT(r.latency_p99_ms, 0.0);
  EXPECT_GE(r.snapshots, 2);
  // Offline, from the recording: the same trajectory, pose by pose.
  const tools::MapRun offline = tools::MapBag(config, r.recording_path, false);
  const auto a = r.run.slam->CorrectedTrajectory();
  const auto b = offline.slam->CorrectedTrajectory();
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) {
    ASSERT_EQ(a[k].first, b[k].first);
    ASSERT_NEAR(a[k].second.x_m, b[k].second.x_m, 1e-6);
    ASSERT_NEAR(a[k].second.y_m, b[k].second.y_m, 1e-6);
  }
  EXPECT_EQ(offline.slam->keyframes().size(), r.run.slam->keyframes().size());
  // live.json holds the figures.
  std::ifstream in(live.out_dir + "/live.json");
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_EQ(j["scan_latency_ms"]["samples"].get<long long>(), r.latency_samples);
  EXPECT_TRUE(std::filesystem::exists(live.out_dir + "/summary.json"));
  // ATE against the emulator's ground truth is measured (same clock as the drivers).
  EXPECT_GT(r.outputs.ate.num_poses, 100);
  EXPECT_LT(r.outputs.ate.rmse_m, 0.05);
}

TEST(LiveRunTest, DeviceListNotMatchingTheRadarsIsAnInputError) {
  Config config;
  config.live.radar_devices = {"/dev/ttyACM0"};
  tools::LiveRunOptions options;
  options.out_dir = std::filesystem::temp_directory_path() / "uwbsar_live_bad";
  EXPECT_THROW(tools::RunLive(config, std::move(options)), InputError);
}

}  // namespace
}  // namespace uwbsar::live
