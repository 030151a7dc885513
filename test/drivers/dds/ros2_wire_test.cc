// Byte compatibility with classic ROS 2 CDR, checked against the project's rosbag
// codecs (drivers/rosbag/ros_codecs.h), which read and write real ROS 2 bags:
// what Cyclone serialises for our IDL types decodes with them, and what they encode
// (as a ROS 2 node would send it) reaches Ros2Subscriber with every value intact.
#include <gtest/gtest.h>

#include "drivers/dds/ros2_convert.h"
#include "drivers/dds/ros2_subscriber.h"
#include "drivers/dds/ros2_types.h"
#include "drivers/rosbag/ros_codecs.h"
#include "test/drivers/dds/dds_test_util.h"
#include "test/drivers/dds/raw_cdr.h"

namespace uwbsar::dds {
namespace {

using testing::RawCdrEndpoint;
using testing::WaitFor;

class Ros2WireTest : public ::testing::Test {
 protected:
  /// Writes `sample` with the typed API and returns what went on the wire.
  std::vector<std::uint8_t> Serialise(RawCdrEndpoint& endpoint, const void* sample) {
    Check(dds_write(endpoint.writer(), sample), "dds_write");
    std::vector<std::vector<std::uint8_t>> got;
    WaitFor([&] {
      got = endpoint.Take();
      return !got.empty();
    });
    return got.empty() ? std::vector<std::uint8_t>{} : got[0];
  }

  DdsConfig config_ = testing::LoopbackConfig();
  Participant robot_{config_};
  Participant ours_{config_};
};

TEST_F(Ros2WireTest, CycloneFloat32MultiArrayIsRosCdr) {
  RawCdrEndpoint endpoint(robot_, &std_msgs_msg_dds__Float32MultiArray__desc, "/radar");
  std::vector<float> data = {1.0f, -2.5f, 1e-3f};
  std_msgs_msg_dds__MultiArrayDimension_ dim{const_cast<char*>("samples"), 3, 3};
  std_msgs_msg_dds__Float32MultiArray_ msg{};
  msg.layout_.dim_._buffer = &dim;
  msg.layout_.dim_._length = msg.layout_.dim_._maximum = 1;
  msg.layout_.data_offset_ = 7;
  msg.data_._buffer = data.data();
  msg.data_._length = msg.data_._maximum = 3;
  const std::vector<std::uint8_t> wire = Serialise(endpoint, &msg);
  ASSERT_FALSE(wire.empty());

  rosbag::Float32MultiArray decoded;
  rosbag::DecodeCdr(wire.data(), wire.size(), &decoded);
  ASSERT_EQ(decoded.dim.size(), 1u);
  EXPECT_EQ(decoded.dim[0].label, "samples");
  EXPECT_EQ(decoded.dim[0].size, 3u);
  EXPECT_EQ(decoded.data_offset, 7u);
  EXPECT_EQ(decoded.data, data);
  // Byte for byte what ROS 2 would send (Cyclone may pad the end to 4 bytes).
  std::vector<std::uint8_t> ros;
  rosbag::EncodeCdr(decoded, &ros);
  ASSERT_GE(wire.size(), ros.size());
  EXPECT_LE(wire.size() - ros.size(), 3u);
  EXPECT_TRUE(std::equal(ros.begin() + 4, ros.end(), wire.begin() + 4));
  EXPECT_EQ(wire[0], 0x00);  // CDR little-endian, classic (XCDR1)
  EXPECT_EQ(wire[1], 0x01);
}

TEST_F(Ros2WireTest, CycloneOdometryIsRosCdr) {
  RawCdrEndpoint endpoint(robot_, &nav_msgs_msg_dds__Odometry__desc, "/odom");
  nav_msgs_msg_dds__Odometry_ msg{};
  msg.header_.stamp_ = {17, 25};
  msg.header_.frame_id_ = const_cast<char*>("odom");
  msg.child_frame_id_ = const_cast<char*>("base_link");
  msg.pose_.pose_ = PoseToDds({1.0, 2.0, 0.3});
  for (int i = 0; i < 36; ++i) msg.pose_.covariance_[i] = i;
  msg.twist_.twist_.linear_ = {0.5, 0.0, 0.0};
  msg.twist_.twist_.angular_ = {0.0, 0.0, -0.1};
  msg.twist_.covariance_[35] = 9.0;
  const std::vector<std::uint8_t> wire = Serialise(endpoint, &msg);
  ASSERT_FALSE(wire.empty());

  rosbag::Odometry decoded;
  rosbag::DecodeCdr(wire.data(), wire.size(), &decoded);
  EXPECT_EQ(decoded.header.stamp.sec, 17);
  EXPECT_EQ(decoded.header.stamp.nanosec, 25u);
  EXPECT_EQ(decoded.header.frame_id, "odom");
  EXPECT_EQ(decoded.child_frame_id, "base_link");
  EXPECT_DOUBLE_EQ(decoded.position.y, 2.0);
  EXPECT_NEAR(rosbag::YawFromQuaternion(decoded.orientation), 0.3, 1e-12);
  EXPECT_EQ(decoded.pose_covariance[35], 35.0);
  EXPECT_EQ(decoded.linear.x, 0.5);
  EXPECT_EQ(decoded.angular.z, -0.1);
  EXPECT_EQ(decoded.twist_covariance[35], 9.0);
  std::vector<std::uint8_t> ros;
  rosbag::EncodeCdr(decoded, &ros);
  ASSERT_GE(wire.size(), ros.size());
  EXPECT_TRUE(std::equal(ros.begin() + 4, ros.end(), wire.begin() + 4));
}

TEST_F(Ros2WireTest, RosEncodedSamplesReachTheSubscriberIntact) {
  testing::EventLog events;
  std::mutex mutex;
  std::vector<RadarMessage> radar;
  std::vector<OdometryMessage> odometry;
  Ros2Subscriber::Callbacks callbacks;
  callbacks.on_radar = [&](RadarMessage&& m) {
    std::lock_guard<std::mutex> lock(mutex);
    radar.push_back(std::move(m));
  };
  callbacks.on_odometry = [&](OdometryMessage&& m) {
    std::lock_guard<std::mutex> lock(mutex);
    odometry.push_back(std::move(m));
  };
  Ros2Subscriber subscriber(ours_, config_, {"/radar"}, "/odom", callbacks);

  RawCdrEndpoint radar_out(robot_, &std_msgs_msg_dds__Float32MultiArray__desc, "/radar");
  RawCdrEndpoint odom_out(robot_, &nav_msgs_msg_dds__Odometry__desc, "/odom");
  // One typed sample each teaches the endpoints their sertype (see WriteCdr).
  std_msgs_msg_dds__Float32MultiArray_ probe{};
  float one = 1.0f;
  probe.data_._buffer = &one;
  probe.data_._length = probe.data_._maximum = 1;
  ASSERT_FALSE(Serialise(radar_out, &probe).empty());
  nav_msgs_msg_dds__Odometry_ odom_probe{};
  odom_probe.pose_.pose_.orientation_.w_ = 1.0;
  odom_probe.header_.frame_id_ = const_cast<char*>("");
  odom_probe.child_frame_id_ = const_cast<char*>("");
  ASSERT_FALSE(Serialise(odom_out, &odom_probe).empty());
  ASSERT_TRUE(WaitFor([&] {
    std::lock_guard<std::mutex> lock(mutex);
    return radar.size() == 1 && odometry.size() == 1;
  }));

  rosbag::Float32MultiArray scan;
  scan.dim = {{"range", 5, 5}};
  scan.data = {0.0f, 0.25f, -0.5f, 1e6f, 3.0f};
  std::vector<std::uint8_t> bytes;
  rosbag::EncodeCdr(scan, &bytes);
  radar_out.WriteCdr(bytes);
  rosbag::Odometry odom;
  odom.header.stamp = {50, 500};
  odom.header.frame_id = "odom";
  odom.child_frame_id = "base_footprint";
  odom.position = {3.0, -4.0, 0.0};
  odom.orientation = rosbag::QuaternionFromYaw(-2.0);
  odom.linear = {0.7, 0.0, 0.0};
  odom.angular = {0.0, 0.0, 0.2};
  rosbag::EncodeCdr(odom, &bytes);
  odom_out.WriteCdr(bytes);

  ASSERT_TRUE(WaitFor([&] {
    std::lock_guard<std::mutex> lock(mutex);
    return radar.size() == 2 && odometry.size() == 2;
  }));
  EXPECT_EQ(radar[1].scan.samples, scan.data);
  EXPECT_EQ(radar[1].scan.sensor_id, 0);
  const OdometryMessage& m = odometry[1];
  EXPECT_EQ(m.sample.stamp_ns, 50000000500LL);
  EXPECT_EQ(m.frame_id, "odom");
  EXPECT_EQ(m.child_frame_id, "base_footprint");
  EXPECT_DOUBLE_EQ(m.sample.T_world_robot.x_m, 3.0);
  EXPECT_DOUBLE_EQ(m.sample.T_world_robot.y_m, -4.0);
  EXPECT_NEAR(m.sample.T_world_robot.yaw_rad, -2.0, 1e-12);
  EXPECT_DOUBLE_EQ(m.sample.linear_velocity_mps, 0.7);
  EXPECT_DOUBLE_EQ(m.sample.angular_velocity_radps, 0.2);
}

}  // namespace
}  // namespace uwbsar::dds
