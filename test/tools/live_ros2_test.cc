// `uwbsar run --source ros2` driven by an independent ROS 2 peer (the
// Python `cyclonedds` package playing a simulated bag, test/tools/ros2_bag_player.py) on
// loopback. A: the live result matches `uwbsar map` on the same bag; B: an independent
// subscriber decodes the published map and path to the files written to disk; C: publisher
// gone mid-run, duplicate and out-of-order samples and a wrong type on a topic are
// reported and survived, and the recording holds every message sent.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <thread>

#include "drivers/logs/tum_reader.h"
#include "drivers/rosbag/bag_reader.h"
#include "imaging/occupancy_grid.h"
#include "slam/app_config.h"
#include "slam/live/live_runner.h"
#include "slam/map_job.h"
#include "test/drivers/dds/dds_test_util.h"
#include "test/shared_data.h"
#include "test/slam/live/live_test_util.h"

namespace uwbsar::tools {
namespace {

namespace fs = std::filesystem;
using dds::testing::BackgroundCommand;
using live::AcceptedPairs;

std::string PlayerCommand(const std::string& python, const std::string& mode,
                          const std::string& args) {
  return dds::testing::PythonPeerCommand(python, "test/tools/ros2_bag_player.py", mode, args);
}

/// The JSON object a peer printed last; {"error": output} when there is none.
nlohmann::json LastJson(const std::string& output) {
  const std::size_t start = output.rfind("\n{");
  const std::string text = start == std::string::npos ? output : output.substr(start + 1);
  const nlohmann::json parsed = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (parsed.is_discarded())
    return {{"error", output.substr(output.size() > 2000 ? output.size() - 2000 : 0)}};
  return parsed;
}

struct Fixture {
  std::string python, dir, bag;
  Config config;
};

/// A simulated seed_lab bag and a config talking DDS on loopback; false if no venv.
bool Prepare(const std::string& name, Fixture* f) {
  f->python = dds::testing::VenvPython();
  if (f->python.empty()) return false;
  f->dir = (fs::temp_directory_path() / ("uwbsar_ros2_" + name + "_" + std::to_string(::getpid())))
               .string();
  fs::remove_all(f->dir);
  fs::create_directories(f->dir);
  f->bag = f->dir + "/sim";
  const std::string cmd = std::string(UWBSAR_BIN) + " --quiet simulate --map " +
                          ::uwbsar::testing::SeedLabLidarMap() + " --out " + f->bag +
                          " > /dev/null";
  if (std::system(cmd.c_str()) != 0) throw std::runtime_error("simulate failed: " + cmd);
  const DdsConfig loopback = dds::testing::LoopbackConfig();
  f->config.dds.domain_id = loopback.domain_id;
  f->config.dds.network_interface = loopback.network_interface;
  f->config.live.snapshot_period_s = 5.0;
  return true;
}

/// Runs `uwbsar run --source ros2` in this process until `players` (run one after the
/// other, `gap_s` apart) have finished.
slam::LiveRunResult RunWhilePlaying(const Fixture& f, const std::vector<std::string>& players,
                                    double gap_s, std::vector<nlohmann::json>* sent) {
  std::atomic<bool> stop{false};
  std::thread driver([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(500));  // uwbsar is up
    for (std::size_t i = 0; i < players.size(); ++i) {
      if (i > 0) std::this_thread::sleep_for(std::chrono::duration<double>(gap_s));
      BackgroundCommand player(PlayerCommand(f.python, "play", players[i]));
      int status = -1;
      const std::string out = player.Finish(&status);
      sent->push_back(status == 0 ? LastJson(out) : nlohmann::json{{"error", out}});
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
    stop = true;
  });
  slam::LiveRunOptions options;
  options.source = "ros2";
  options.out_dir = f.dir + "/live";
  options.recording_dir = f.dir + "/recording";
  options.stop = &stop;
  options.quiet = true;
  slam::LiveRunResult result = slam::RunLive(f.config, std::move(options));
  driver.join();
  return result;
}

TEST(LiveRos2Test, A_B_PeerDrivesALiveRunMatchingOfflineAndPublishesWhatIsOnDisk) {
  UWBSAR_NEED_SEED_LAB_MAP();
  Fixture f;
  if (!Prepare("ab", &f)) GTEST_SKIP() << "UWBSAR_VENV not set (make test sets it)";
  BackgroundCommand listener(PlayerCommand(f.python, "listen", "--idle 6 --timeout 300"));
  std::vector<nlohmann::json> sent;
  const slam::LiveRunResult live = RunWhilePlaying(f, {"--bag " + f.bag + " --speed 2"}, 0, &sent);
  ASSERT_EQ(sent.size(), 1u);
  ASSERT_FALSE(sent[0].contains("error")) << sent[0].dump();
  int status = -1;
  const nlohmann::json heard = LastJson(listener.Finish(&status));
  ASSERT_FALSE(heard.contains("error")) << heard["error"].get<std::string>();

  // A: the same result as `uwbsar map` on the bag the peer played.
  const slam::MapRun offline = slam::MapBag(f.config, f.bag, false);
  const AteResult offline_ate =
      slam::TrajectoryError(offline.slam->CorrectedTrajectory(), offline.ground_truth);
  const AteResult live_ate =
      slam::TrajectoryError(live.run.slam->CorrectedTrajectory(), offline.ground_truth);
  std::printf(
      "A: live over DDS: %zu keyframes, %zu accepted loops, ATE %.2f cm; uwbsar map: "
      "%zu keyframes, %zu loops, ATE %.2f cm; %lld scans, %lld odometry received\n",
      live.run.slam->keyframes().size(), AcceptedPairs(*live.run.slam).size(),
      100 * live_ate.rmse_m, offline.slam->keyframes().size(), AcceptedPairs(*offline.slam).size(),
      100 * offline_ate.rmse_m, live.scans_received, live.odometry_received);
  EXPECT_EQ(live.scans_received, sent[0]["radar"].get<long long>());
  EXPECT_EQ(live.dropped_from_processing, 0);
  ASSERT_GT(live_ate.num_poses, 100);
  EXPECT_LT(std::abs(live_ate.rmse_m - offline_ate.rmse_m), 0.01);
  EXPECT_EQ(AcceptedPairs(*live.run.slam), AcceptedPairs(*offline.slam));
  // The recording, mapped offline, gives the live trajectory.
  const slam::MapRun replay = slam::MapBag(f.config, live.recording_path, false);
  const auto a = live.run.slam->CorrectedTrajectory();
  const auto b = replay.slam->CorrectedTrajectory();
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) {
    ASSERT_NEAR(a[k].second.x_m, b[k].second.x_m, 1e-6) << k;
    ASSERT_NEAR(a[k].second.y_m, b[k].second.y_m, 1e-6) << k;
  }

  // B: the last map and path the subscriber heard are the files on disk.
  ASSERT_TRUE(heard.contains("map")) << heard.dump().substr(0, 300);
  ASSERT_TRUE(heard.contains("path"));
  const OccupancyGrid grid = LoadOccupancyGrid(f.dir + "/live/map.yaml");
  const nlohmann::json& map = heard["map"];
  EXPECT_EQ(map["frame"], f.config.dds.map_frame);
  ASSERT_EQ(map["width"].get<int>(), grid.cols);
  ASSERT_EQ(map["height"].get<int>(), grid.rows);
  EXPECT_NEAR(map["resolution"].get<double>(), grid.resolution_m, 1e-6);
  EXPECT_NEAR(map["origin"][0].get<double>(), grid.origin.x_m, 1e-9);
  EXPECT_NEAR(map["origin"][1].get<double>(), grid.origin.y_m, 1e-9);
  const std::vector<int> data = map["data"].get<std::vector<int>>();
  ASSERT_EQ(data.size(), grid.cells.size());
  int mismatched = 0;
  for (int r = 0; r < grid.rows; ++r) {  // ROS rows start at the origin (bottom) row
    for (int c = 0; c < grid.cols; ++c) {
      mismatched +=
          data[static_cast<std::size_t>(r) * grid.cols + c] != grid.At(grid.rows - 1 - r, c);
    }
  }
  EXPECT_EQ(mismatched, 0);
  const std::vector<OdometrySample> tum = ReadTum(f.dir + "/live/trajectory.tum");
  const nlohmann::json& poses = heard["path"]["poses"];
  ASSERT_EQ(poses.size(), tum.size());
  double worst_m = 0.0;
  for (std::size_t k = 0; k < tum.size(); ++k) {
    worst_m = std::max({worst_m, std::abs(poses[k][2].get<double>() - tum[k].T_world_robot.x_m),
                        std::abs(poses[k][3].get<double>() - tum[k].T_world_robot.y_m)});
  }
  std::printf(
      "B: map %dx%d cells identical to map.pgm (%d differ); path %zu poses, worst "
      "difference to trajectory.tum %.2e m; heard %s\n",
      grid.cols, grid.rows, mismatched, tum.size(), worst_m, heard["counts"].dump().c_str());
  EXPECT_LT(worst_m, 1e-6);  // trajectory.tum keeps 9 decimals
  ASSERT_TRUE(heard.contains("loops"));
  EXPECT_GT(heard["counts"]["pose"].get<int>(), 10);
  // /tf: map -> odom composed with the odometry at the pose's stamp is the published pose.
  ASSERT_TRUE(heard.contains("tf"));
  ASSERT_TRUE(heard.contains("pose"));
  const nlohmann::json& tf = heard["tf"]["transforms"][0];
  const nlohmann::json& pose = heard["pose"];
  EXPECT_EQ(tf["frame"], "map");
  EXPECT_EQ(tf["child"], "odom");
  ASSERT_EQ(tf["sec"], pose["sec"]);
  ASSERT_EQ(tf["nanosec"], pose["nanosec"]);
  const TimestampNs pose_ns =
      pose["sec"].get<TimestampNs>() * 1000000000 + pose["nanosec"].get<TimestampNs>();
  const Pose2 T_map_odom{tf["pose"][0].get<double>(), tf["pose"][1].get<double>(),
                         tf["pose"][2].get<double>()};
  const OdometryEntry* odom = nullptr;
  for (const OdometryEntry& e : live.run.slam->odometry()) {
    if (e.stamp_ns == pose_ns) odom = &e;
  }
  ASSERT_NE(odom, nullptr);
  const Pose2 composed = T_map_odom * odom->T_world_robot;
  EXPECT_NEAR(composed.x_m, pose["pose"][0].get<double>(), 1e-9);
  EXPECT_NEAR(composed.y_m, pose["pose"][1].get<double>(), 1e-9);
}

TEST(LiveRos2Test, C_PublisherGoneDuplicatesDisorderAndWrongTypeAreSurvived) {
  UWBSAR_NEED_SEED_LAB_MAP();
  Fixture f;
  if (!Prepare("c", &f)) GTEST_SKIP() << "UWBSAR_VENV not set (make test sets it)";
  // A wrong type on the odometry topic while the bag plays.
  BackgroundCommand wrong(dds::testing::PeerCommand(f.python, "wrongtype", "--linger 6"));
  std::vector<nlohmann::json> sent;
  const slam::LiveRunResult live = RunWhilePlaying(
      f,
      {"--bag " + f.bag + " --speed 2 --duration 12 --duplicate-every 50 --out-of-order-at 100",
       "--bag " + f.bag + " --speed 2 --start 16 --duration 12"},
      2.0, &sent);
  int status = -1;
  wrong.Finish(&status);
  ASSERT_EQ(sent.size(), 2u);
  for (const auto& s : sent) ASSERT_FALSE(s.contains("error")) << s.dump();
  for (const auto& [kind, count] : live.faults) std::printf("C: %s: %lld\n", kind.c_str(), count);
  auto count = [&](const std::string& needle) {
    long long n = 0;
    for (const auto& [kind, c] : live.faults) n += kind.find(needle) != std::string::npos ? c : 0;
    return n;
  };
  EXPECT_GE(count("publisher_gone"), 1);
  EXPECT_GE(count("duplicate"), sent[0]["duplicates"].get<long long>());
  EXPECT_GE(count("out_of_order"), 1);
  EXPECT_GE(count("wrong_type"), 1);
  // Nothing lost from the recording: every radar and odometry sample sent, duplicates and
  // disorder included.
  std::map<std::string, long long> recorded;
  rosbag::BagReader reader(live.recording_path);
  rosbag::BagMessage msg;
  while (reader.Next(&msg)) ++recorded[reader.Info().topics[msg.topic].name];
  long long radar_sent = 0, odometry_sent = 0;
  for (const auto& s : sent) {
    radar_sent += s["radar"].get<long long>();
    odometry_sent += s["odometry"].get<long long>();
  }
  std::printf("C: sent %lld scans, %lld odometry; recorded %lld + %lld scans, %lld odometry\n",
              radar_sent, odometry_sent, recorded["/UWBradar0/readings"],
              recorded["/UWBradar1/readings"], recorded["/odom"]);
  EXPECT_EQ(recorded["/UWBradar0/readings"] + recorded["/UWBradar1/readings"], radar_sent);
  EXPECT_EQ(recorded["/odom"], odometry_sent);
  EXPECT_FALSE(live.run.slam->keyframes().empty());
}

// The robot's own serial devices (emulated), results published for RViz2 on a second
// machine: a subscriber hears the map that is on disk and poses.
TEST(LiveRos2Test, SerialRunPublishesItsResultsWhenAsked) {
  UWBSAR_NEED_SEED_LAB_MAP();
  const std::string python = dds::testing::VenvPython();
  if (python.empty()) GTEST_SKIP() << "UWBSAR_VENV not set (make test sets it)";
  Config config;
  const DdsConfig loopback = dds::testing::LoopbackConfig();
  config.dds.domain_id = loopback.domain_id;
  config.dds.network_interface = loopback.network_interface;
  config.dds.publish_in_serial_mode = true;
  config.live.snapshot_period_s = 2.0;
  BackgroundCommand listener(PlayerCommand(python, "listen", "--idle 4 --timeout 120"));
  const live::EmulatedRun run = live::RunEmulated(config, "ros2_serial", 2.0, 14.0);
  int status = -1;
  const nlohmann::json heard = LastJson(listener.Finish(&status));
  ASSERT_FALSE(heard.contains("error")) << heard["error"].get<std::string>();
  ASSERT_TRUE(heard.contains("map"));
  const OccupancyGrid grid = LoadOccupancyGrid(run.out_dir + "/map.yaml");
  EXPECT_EQ(heard["map"]["width"].get<int>(), grid.cols);
  EXPECT_EQ(heard["map"]["height"].get<int>(), grid.rows);
  EXPECT_GT(heard["counts"]["pose"].get<int>(), 5);
  EXPECT_GT(heard["counts"]["tf"].get<int>(), 5);
  std::printf("serial run published %s\n", heard["counts"].dump().c_str());
}

}  // namespace
}  // namespace uwbsar::tools
