#include "drivers/dds/ros2_convert.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace uwbsar::dds {
namespace {

TEST(Ros2ConvertTest, StampsRoundTripIncludingBeforeTheEpoch) {
  for (const TimestampNs t : {0LL, 1LL, 1700000000123456789LL, -1LL, -1500000000LL}) {
    const auto stamp = NsToStamp(t);
    EXPECT_LT(stamp.nanosec_, 1000000000u);
    EXPECT_EQ(StampToNs(stamp), t);
  }
  const auto before = NsToStamp(-1);
  EXPECT_EQ(before.sec_, -1);
  EXPECT_EQ(before.nanosec_, 999999999u);
}

TEST(Ros2ConvertTest, PoseYawSurvivesTheQuaternion) {
  for (const double yaw : {0.0, 0.5, -2.0, 3.1}) {
    const auto pose = PoseToDds({1.0, -2.0, yaw});
    EXPECT_DOUBLE_EQ(pose.position_.x_, 1.0);
    EXPECT_DOUBLE_EQ(pose.position_.y_, -2.0);
    EXPECT_NEAR(YawFromQuaternion(pose.orientation_.x_, pose.orientation_.y_, pose.orientation_.z_,
                                  pose.orientation_.w_),
                yaw, 1e-12);
  }
  // Not normalised: same yaw.
  EXPECT_NEAR(YawFromQuaternion(0, 0, 2 * std::sin(0.3), 2 * std::cos(0.3)), 0.6, 1e-12);
}

nav_msgs_msg_dds__Odometry_ MakeOdometry() {
  nav_msgs_msg_dds__Odometry_ msg{};
  msg.header_.stamp_ = NsToStamp(5000000123LL);
  msg.pose_.pose_ = PoseToDds({0.25, 0.75, -0.4});
  msg.twist_.twist_.linear_.x_ = 0.3;
  msg.twist_.twist_.angular_.z_ = -0.2;
  return msg;
}

TEST(Ros2ConvertTest, OdometryBecomesPlanarSample) {
  OdometrySample sample;
  std::string why;
  ASSERT_TRUE(OdometryFromDds(MakeOdometry(), &sample, &why)) << why;
  EXPECT_EQ(sample.stamp_ns, 5000000123LL);
  EXPECT_DOUBLE_EQ(sample.T_world_robot.x_m, 0.25);
  EXPECT_DOUBLE_EQ(sample.T_world_robot.y_m, 0.75);
  EXPECT_NEAR(sample.T_world_robot.yaw_rad, -0.4, 1e-12);
  EXPECT_DOUBLE_EQ(sample.linear_velocity_mps, 0.3);
  EXPECT_DOUBLE_EQ(sample.angular_velocity_radps, -0.2);
}

TEST(Ros2ConvertTest, UnusableOdometryIsRejectedWithAReason) {
  OdometrySample sample;
  std::string why;
  auto nan = MakeOdometry();
  nan.pose_.pose_.position_.y_ = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(OdometryFromDds(nan, &sample, &why));
  EXPECT_NE(why.find("not finite"), std::string::npos);
  auto zero = MakeOdometry();
  zero.pose_.pose_.orientation_ = {0, 0, 0, 0};
  EXPECT_FALSE(OdometryFromDds(zero, &sample, &why));
  EXPECT_NE(why.find("zero quaternion"), std::string::npos);
}

TEST(Ros2ConvertTest, GridRowsAreFlippedToStartAtTheOrigin) {
  OccupancyGrid grid;
  grid.rows = 3;
  grid.cols = 2;
  grid.cells = {1, 2,     // top row
                3, 4,     //
                5, 100};  // bottom row: holds the origin cell
  EXPECT_EQ(GridCellsBottomUp(grid), (std::vector<std::int8_t>{5, 100, 3, 4, 1, 2}));
}

}  // namespace
}  // namespace uwbsar::dds
