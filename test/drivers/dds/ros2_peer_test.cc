// Both directions against an implementation that is not ours: ros2_peer.py defines
// the ROS 2 types itself and talks through the `cyclonedds` Python package (its own
// bundled Cyclone DDS 11, with XTypes type information; ours is Debian's 0.10.2
// without), over the loopback network. Skipped when UWBSAR_VENV is unset.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "drivers/dds/ros2_publisher.h"
#include "drivers/dds/ros2_subscriber.h"
#include "test/drivers/dds/dds_test_util.h"

namespace uwbsar::dds {
namespace {

using testing::BackgroundCommand;
using testing::PeerCommand;
using testing::WaitFor;

class Ros2PeerTest : public testing::CollectingSubscriberTest {
 protected:
  void SetUp() override {
    python_ = testing::VenvPython();
    if (python_.empty()) GTEST_SKIP() << "UWBSAR_VENV is unset: cannot run ros2_peer.py";
  }
  void Subscribe(const std::vector<std::string>& radar, const std::string& odom) {
    SubscribeOn(participant_, config_, radar, odom);
  }
  /// Runs the peer to completion; its stdout's last line parsed as JSON.
  nlohmann::json RunPeer(const std::string& mode, const std::string& args = "") {
    BackgroundCommand peer(PeerCommand(python_, mode, args));
    EXPECT_TRUE(peer.started());
    int status = -1;
    const std::string out = peer.Finish(&status);
    EXPECT_EQ(status, 0) << out;
    const auto last_line = out.find_last_of('\n', out.size() - 2);
    try {
      return nlohmann::json::parse(last_line == std::string::npos ? out : out.substr(last_line));
    } catch (const std::exception&) {
      ADD_FAILURE() << "peer output is not JSON: " << out;
      return {};
    }
  }

  std::string python_;
  DdsConfig config_ = testing::LoopbackConfig();
  Participant participant_{config_};
};

TEST_F(Ros2PeerTest, RadarAndOdometryFromThePeerAreDecodedAndItsExitIsReported) {
  Subscribe({"/UWBradar0/readings", "/UWBradar1/readings"}, "/odom");
  const nlohmann::json sent = RunPeer("publish", "--count 10 --samples 64 --disorder");
  ASSERT_TRUE(sent.contains("radar")) << sent.dump();
  ASSERT_TRUE(WaitFor([&] {
    std::lock_guard<std::mutex> lock(mutex_);
    return radar_.size() == 20 && odometry_.size() == 13;
  }));
  std::lock_guard<std::mutex> lock(mutex_);
  int per_sensor[2] = {0, 0};
  for (const RadarMessage& m : radar_) {
    ASSERT_EQ(m.scan.samples.size(), 64u);
    const int i = per_sensor[m.scan.sensor_id]++;  // in order per topic
    EXPECT_FLOAT_EQ(m.scan.samples[0], static_cast<float>(m.scan.sensor_id * 1000 + i));
    EXPECT_FLOAT_EQ(m.scan.samples[63], static_cast<float>(m.scan.sensor_id * 1000 + i + 31.5));
    EXPECT_GT(m.scan.stamp_ns, 1600000000000000000LL);  // the peer's wall clock
  }
  EXPECT_EQ(per_sensor[0], 10);
  EXPECT_EQ(per_sensor[1], 10);
  for (int i = 0; i < 10; ++i) {
    const OdometryMessage& m = odometry_[static_cast<std::size_t>(i)];
    EXPECT_NEAR(NsToSeconds(m.sample.stamp_ns), 1000.0 + 0.1 * i, 1e-6);
    EXPECT_NEAR(m.sample.T_world_robot.x_m, 0.1 * i, 1e-12);
    EXPECT_NEAR(m.sample.T_world_robot.y_m, -0.05 * i, 1e-12);
    EXPECT_NEAR(m.sample.T_world_robot.yaw_rad, 0.01 * i, 1e-12);
    EXPECT_DOUBLE_EQ(m.sample.linear_velocity_mps, 0.5);
    EXPECT_DOUBLE_EQ(m.sample.angular_velocity_radps, 0.1);
    EXPECT_EQ(m.child_frame_id, "base_footprint");
    EXPECT_TRUE(m.in_order);
  }
  // --disorder: a duplicate stamp, an earlier one, then a good one.
  EXPECT_FALSE(odometry_[10].in_order);
  EXPECT_FALSE(odometry_[11].in_order);
  EXPECT_TRUE(odometry_[12].in_order);
  EXPECT_EQ(events_.Count(DdsEventKind::kDuplicate), 1);
  EXPECT_EQ(events_.Count(DdsEventKind::kOutOfOrder), 1);
  // The peer process has exited: each of its publishers is gone.
  EXPECT_TRUE(WaitFor([&] { return events_.Count(DdsEventKind::kPublisherGone) == 3; }));
  EXPECT_EQ(subscriber_->MatchedPublishers("/odom"), 0);
}

TEST_F(Ros2PeerTest, BestEffortPeerIsReceivedByABestEffortSubscription) {
  config_.reliability = "best_effort";
  Subscribe({"/UWBradar0/readings"}, "/odom");
  RunPeer("publish", "--radar-topics /UWBradar0/readings --count 5 --best-effort --period 0.02");
  // Best effort on loopback: expect (nearly) everything.
  EXPECT_TRUE(WaitFor(
      [&] {
        std::lock_guard<std::mutex> lock(mutex_);
        return odometry_.size() >= 4 && radar_.size() >= 4;
      },
      3.0));
}

TEST_F(Ros2PeerTest, GarbledOdometryBytesAreDroppedAndTheNextSampleArrives) {
  Subscribe({}, "/odom");
  RunPeer("garbled");
  ASSERT_TRUE(WaitFor([&] {
    std::lock_guard<std::mutex> lock(mutex_);
    return !odometry_.empty();
  }));
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  std::lock_guard<std::mutex> lock(mutex_);
  ASSERT_EQ(odometry_.size(), 1u);
  EXPECT_DOUBLE_EQ(odometry_[0].sample.T_world_robot.x_m, 1.5);
  EXPECT_DOUBLE_EQ(odometry_[0].sample.T_world_robot.y_m, 2.5);
}

TEST_F(Ros2PeerTest, PeerPublishingAnotherTypeOnOdomIsReported) {
  Subscribe({}, "/odom");
  RunPeer("wrongtype", "--linger 0.5");
  ASSERT_TRUE(WaitFor([&] { return events_.Count(DdsEventKind::kWrongType) >= 1; }));
  EXPECT_EQ(events_.Detail(DdsEventKind::kWrongType),
            "topic /odom published with type geometry_msgs::msg::dds_::PoseStamped_, expected "
            "nav_msgs::msg::dds_::Odometry_");
}

TEST_F(Ros2PeerTest, PeerDecodesMapPosePathAndLoopsWePublish) {
  Ros2Publisher publisher(participant_, config_);
  OccupancyGrid grid;
  grid.rows = 3;
  grid.cols = 2;
  grid.resolution_m = 0.1;
  grid.origin = {-1.0, -2.0, 0.5};
  grid.cells = {100, 100, 0, -1, 0, 0};               // top row first
  publisher.PublishMap(grid, 1700000001250000000LL);  // before the peer exists: latched

  BackgroundCommand peer(PeerCommand(python_, "subscribe"));
  ASSERT_TRUE(peer.started());
  ASSERT_TRUE(WaitFor([&] {
    return publisher.MatchedSubscribers("/uwbsar/pose") > 0 &&
           publisher.MatchedSubscribers("/uwbsar/path") > 0 &&
           publisher.MatchedSubscribers("/uwbsar/loops") > 0;
  }));
  EXPECT_TRUE(publisher.PublishPose(2000000000LL, {0.5, 0.25, -0.75}));
  publisher.PublishPath(2000000000LL,
                        {{1000000000LL, {0, 0, 0}}, {2000000000LL, {0.5, 0.25, -0.75}}});
  publisher.PublishLoops(2000000000LL, {{{0, 0}, {0.5, 0.25}}});
  int status = -1;
  const std::string out = peer.Finish(&status);
  ASSERT_EQ(status, 0) << out;
  const nlohmann::json got = nlohmann::json::parse(out.substr(out.find('{')));

  const auto& map = got.at("map");
  EXPECT_EQ(map.at("frame"), "map");
  EXPECT_EQ(map.at("sec"), 1700000001);
  EXPECT_EQ(map.at("nanosec"), 250000000);
  EXPECT_EQ(map.at("width"), 2);
  EXPECT_EQ(map.at("height"), 3);
  EXPECT_NEAR(map.at("resolution").get<double>(), 0.1, 1e-7);
  EXPECT_NEAR(map.at("origin")[2].get<double>(), 0.5, 1e-12);
  EXPECT_EQ(map.at("data").get<std::vector<int>>(), (std::vector<int>{0, 0, 0, -1, 100, 100}));

  const auto& pose = got.at("pose").at("pose");
  EXPECT_DOUBLE_EQ(pose[0].get<double>(), 0.5);
  EXPECT_NEAR(pose[2].get<double>(), -0.75, 1e-12);
  const auto& path = got.at("path").at("poses");
  ASSERT_EQ(path.size(), 2u);
  EXPECT_EQ(path[1][0], 2);
  EXPECT_DOUBLE_EQ(path[1][3].get<double>(), 0.25);
  const auto& markers = got.at("loops").at("markers");
  ASSERT_EQ(markers.size(), 2u);
  EXPECT_EQ(markers[0].at("action"), 3);  // DELETEALL
  EXPECT_EQ(markers[1].at("type"), 5);    // LINE_LIST
  EXPECT_EQ(markers[1].at("ns"), "loops");
  EXPECT_EQ(markers[1].at("points").get<std::vector<std::vector<double>>>(),
            (std::vector<std::vector<double>>{{0, 0}, {0.5, 0.25}}));
  EXPECT_EQ(markers[1].at("mesh_use_embedded_materials"), false);
}

}  // namespace
}  // namespace uwbsar::dds
