// What Ros2Publisher puts on the wire, taken as raw CDR and decoded field by field
// with the project's own CDR reader (drivers/rosbag/cdr_reader.h, written from the
// OMG CDR rules, not from Cyclone), in the order of the ROS 2 .msg definitions.
#include "drivers/dds/ros2_publisher.h"

#include <gtest/gtest.h>

#include <cmath>

#include "drivers/dds/ros2_types.h"
#include "drivers/rosbag/cdr_reader.h"
#include "test/drivers/dds/dds_test_util.h"
#include "test/drivers/dds/raw_cdr.h"

namespace uwbsar::dds {
namespace {

using rosbag::CdrReader;
using testing::RawCdrEndpoint;
using testing::WaitFor;

struct Stamp {
  std::int32_t sec;
  std::uint32_t nanosec;
};
struct Header {
  Stamp stamp;
  std::string frame;
};
Header ReadHeader(CdrReader& r) {
  Header h;
  h.stamp.sec = r.Read<std::int32_t>();
  h.stamp.nanosec = r.Read<std::uint32_t>();
  h.frame = r.ReadString();
  return h;
}
// geometry_msgs/Pose as (x, y, yaw), checking it is planar.
Pose2 ReadPose(CdrReader& r) {
  double v[7];
  r.ReadArray(v, 7);
  EXPECT_EQ(v[2], 0.0);
  EXPECT_EQ(v[3], 0.0);
  EXPECT_EQ(v[4], 0.0);
  return {v[0], v[1], 2.0 * std::atan2(v[5], v[6])};
}

class Ros2PublisherTest : public ::testing::Test {
 protected:
  DdsConfig config_ = testing::LoopbackConfig();
  Participant ours_{config_};
  Participant theirs_{config_};
};

std::vector<std::vector<std::uint8_t>> TakeOne(RawCdrEndpoint& endpoint) {
  std::vector<std::vector<std::uint8_t>> got;
  WaitFor([&] {
    for (auto& s : endpoint.Take()) got.push_back(std::move(s));
    return !got.empty();
  });
  return got;
}

TEST_F(Ros2PublisherTest, MapIsLatchedWithRowsFromTheOriginAndOriginPose) {
  Ros2Publisher publisher(ours_, config_);
  OccupancyGrid grid;
  grid.rows = 2;
  grid.cols = 3;
  grid.resolution_m = 0.05;
  grid.origin = {-1.5, 2.0, 0.25};
  grid.cells = {-1, 0,  100,  // top row
                10, 20, 30};
  publisher.PublishMap(grid, 1700000000500000000LL);
  // Subscribed after the map was sent: transient local must still deliver it.
  RawCdrEndpoint late(theirs_, &nav_msgs_msg_dds__OccupancyGrid__desc, "/uwbsar/map",
                      Durability::kTransientLocal, 1);
  const auto got = TakeOne(late);
  ASSERT_EQ(got.size(), 1u);
  CdrReader r(got[0].data(), got[0].size());
  const Header h = ReadHeader(r);
  EXPECT_EQ(h.stamp.sec, 1700000000);
  EXPECT_EQ(h.stamp.nanosec, 500000000u);
  EXPECT_EQ(h.frame, "map");
  EXPECT_EQ(r.Read<std::int32_t>(), 1700000000);  // map_load_time
  EXPECT_EQ(r.Read<std::uint32_t>(), 500000000u);
  EXPECT_FLOAT_EQ(r.Read<float>(), 0.05f);
  EXPECT_EQ(r.Read<std::uint32_t>(), 3u);  // width
  EXPECT_EQ(r.Read<std::uint32_t>(), 2u);  // height
  const Pose2 origin = ReadPose(r);
  EXPECT_DOUBLE_EQ(origin.x_m, -1.5);
  EXPECT_DOUBLE_EQ(origin.y_m, 2.0);
  EXPECT_NEAR(origin.yaw_rad, 0.25, 1e-12);
  std::vector<std::int8_t> data;
  r.ReadSequence(&data);
  EXPECT_EQ(data, (std::vector<std::int8_t>{10, 20, 30, -1, 0, 100}));
  r.ExpectEnd();
}

TEST_F(Ros2PublisherTest, PoseIsThrottledToThePublishPeriodOfSensorTime) {
  config_.publish_pose_period_s = 0.1;
  Ros2Publisher publisher(ours_, config_);
  RawCdrEndpoint reader(theirs_, &geometry_msgs_msg_dds__PoseStamped__desc, "/uwbsar/pose");
  ASSERT_TRUE(WaitFor([&] { return publisher.MatchedSubscribers("/uwbsar/pose") > 0; }));
  EXPECT_TRUE(publisher.PublishPose(1000000000LL, {1.0, 2.0, 0.5}));
  EXPECT_FALSE(publisher.PublishPose(1050000000LL, {1.1, 2.0, 0.5}));
  EXPECT_TRUE(publisher.PublishPose(1100000000LL, {3.0, -4.0, -1.0}));
  EXPECT_TRUE(publisher.PublishPose(1100000000LL, {3.0, -4.0, -1.0}, /*final=*/true));
  std::vector<std::vector<std::uint8_t>> got;
  ASSERT_TRUE(WaitFor([&] {
    for (auto& s : reader.Take()) got.push_back(std::move(s));
    return got.size() >= 3;
  }));
  ASSERT_EQ(got.size(), 3u);
  CdrReader r(got[1].data(), got[1].size());
  const Header h = ReadHeader(r);
  EXPECT_EQ(h.stamp.sec, 1);
  EXPECT_EQ(h.stamp.nanosec, 100000000u);
  EXPECT_EQ(h.frame, "map");
  const Pose2 pose = ReadPose(r);
  EXPECT_DOUBLE_EQ(pose.x_m, 3.0);
  EXPECT_DOUBLE_EQ(pose.y_m, -4.0);
  EXPECT_NEAR(pose.yaw_rad, -1.0, 1e-12);
  r.ExpectEnd();
}

TEST_F(Ros2PublisherTest, PathHoldsOneStampedPosePerKeyframe) {
  config_.map_frame = "world";
  Ros2Publisher publisher(ours_, config_);
  RawCdrEndpoint reader(theirs_, &nav_msgs_msg_dds__Path__desc, "/uwbsar/path");
  ASSERT_TRUE(WaitFor([&] { return publisher.MatchedSubscribers("/uwbsar/path") > 0; }));
  publisher.PublishPath(9000000000LL, {{1000000001LL, {0, 0, 0}}, {2000000002LL, {1, 1, 1.5}}});
  const auto got = TakeOne(reader);
  ASSERT_EQ(got.size(), 1u);
  CdrReader r(got[0].data(), got[0].size());
  EXPECT_EQ(ReadHeader(r).frame, "world");
  ASSERT_EQ(r.ReadSequenceLength(8), 2u);
  const Header h0 = ReadHeader(r);
  EXPECT_EQ(h0.stamp.sec, 1);
  EXPECT_EQ(h0.stamp.nanosec, 1u);
  ReadPose(r);
  const Header h1 = ReadHeader(r);
  EXPECT_EQ(h1.stamp.sec, 2);
  EXPECT_EQ(h1.stamp.nanosec, 2u);
  EXPECT_EQ(h1.frame, "world");
  const Pose2 p1 = ReadPose(r);
  EXPECT_DOUBLE_EQ(p1.x_m, 1.0);
  EXPECT_NEAR(p1.yaw_rad, 1.5, 1e-12);
  r.ExpectEnd();
}

// One visualization_msgs/Marker of ROS 2 Humble, every field in .msg order.
struct Marker {
  Header header;
  std::string ns;
  std::int32_t id, type, action;
  std::vector<double> points_xyz;
  std::uint32_t colors;
  float width, r, g, b, a;
};
Marker ReadMarker(CdrReader& r) {
  Marker m;
  m.header = ReadHeader(r);
  m.ns = r.ReadString();
  m.id = r.Read<std::int32_t>();
  m.type = r.Read<std::int32_t>();
  m.action = r.Read<std::int32_t>();
  ReadPose(r);
  double scale[3];
  r.ReadArray(scale, 3);
  m.width = static_cast<float>(scale[0]);
  m.r = r.Read<float>();
  m.g = r.Read<float>();
  m.b = r.Read<float>();
  m.a = r.Read<float>();
  EXPECT_EQ(r.Read<std::int32_t>(), 0);    // lifetime.sec
  EXPECT_EQ(r.Read<std::uint32_t>(), 0u);  // lifetime.nanosec
  EXPECT_EQ(r.Read<std::uint8_t>(), 0);    // frame_locked
  m.points_xyz.resize(3 * r.ReadSequenceLength(24));
  r.ReadArray(m.points_xyz.data(), m.points_xyz.size());
  m.colors = static_cast<std::uint32_t>(r.ReadSequenceLength(16));
  EXPECT_EQ(r.ReadString(), "");           // texture_resource
  ReadHeader(r);                           // texture.header
  EXPECT_EQ(r.ReadString(), "");           // texture.format
  EXPECT_EQ(r.ReadSequenceLength(1), 0u);  // texture.data
  EXPECT_EQ(r.ReadSequenceLength(8), 0u);  // uv_coordinates
  EXPECT_EQ(r.ReadString(), "");           // text
  EXPECT_EQ(r.ReadString(), "");           // mesh_resource
  EXPECT_EQ(r.ReadString(), "");           // mesh_file.filename
  EXPECT_EQ(r.ReadSequenceLength(1), 0u);  // mesh_file.data
  EXPECT_EQ(r.Read<std::uint8_t>(), 0);    // mesh_use_embedded_materials
  return m;
}

TEST_F(Ros2PublisherTest, LoopsAreDeleteAllThenOneLineListInHumbleMarkerLayout) {
  Ros2Publisher publisher(ours_, config_);
  RawCdrEndpoint reader(theirs_, &visualization_msgs_msg_dds__MarkerArray__desc, "/uwbsar/loops");
  ASSERT_TRUE(WaitFor([&] { return publisher.MatchedSubscribers("/uwbsar/loops") > 0; }));
  publisher.PublishLoops(3000000000LL, {{{0, 0}, {1, 2}}, {{-3, 4}, {5, -6}}});
  const auto got = TakeOne(reader);
  ASSERT_EQ(got.size(), 1u);
  CdrReader r(got[0].data(), got[0].size());
  ASSERT_EQ(r.ReadSequenceLength(4), 2u);
  const Marker clear = ReadMarker(r);
  EXPECT_EQ(clear.action, kMarkerDeleteAll);
  EXPECT_TRUE(clear.points_xyz.empty());
  const Marker lines = ReadMarker(r);
  r.ExpectEnd();
  EXPECT_EQ(lines.header.frame, "map");
  EXPECT_EQ(lines.header.stamp.sec, 3);
  EXPECT_EQ(lines.ns, "loops");
  EXPECT_EQ(lines.type, kMarkerLineList);
  EXPECT_EQ(lines.action, kMarkerAdd);
  EXPECT_GT(lines.width, 0.0f);
  EXPECT_EQ(lines.a, 1.0f);
  EXPECT_EQ(lines.colors, 0u);
  EXPECT_EQ(lines.points_xyz, (std::vector<double>{0, 0, 0, 1, 2, 0, -3, 4, 0, 5, -6, 0}));
}

TEST_F(Ros2PublisherTest, BadTopicNameIsInputError) {
  config_.path_topic = "/uwbsar path";
  EXPECT_THROW(Ros2Publisher(ours_, config_), InputError);
}

}  // namespace
}  // namespace uwbsar::dds
