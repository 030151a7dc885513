#include <gtest/gtest.h>

#include <cmath>

#include "drivers/live/kobuki_odometry.h"
#include "drivers/live/kobuki_protocol.h"

namespace uwbsar::live {
namespace {

KobukiBasicSensorData Data(std::uint16_t t, std::uint16_t left, std::uint16_t right) {
  KobukiBasicSensorData d;
  d.timestamp_ms = t;
  d.left_encoder = left;
  d.right_encoder = right;
  d.battery = 161;
  return d;
}

TEST(KobukiProtocolTest, PacketRoundTripsThroughTheDecoderInAnySplit) {
  const auto packet = EncodeKobukiPacket(Data(65530, 0xABCD, 0x0102));
  EXPECT_EQ(packet[0], 0xAA);
  EXPECT_EQ(packet[1], 0x55);
  EXPECT_EQ(packet[2], 17);  // one sub-payload: id, length 15, data
  KobukiPacketDecoder decoder;
  std::vector<KobukiBasicSensorData> out;
  for (std::uint8_t b : packet) decoder.Push(&b, 1, &out);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].timestamp_ms, 65530);
  EXPECT_EQ(out[0].left_encoder, 0xABCD);
  EXPECT_EQ(out[0].right_encoder, 0x0102);
  EXPECT_EQ(out[0].battery, 161);
}

TEST(KobukiProtocolTest, ChecksumErrorDropsThePacketAndTheNextOneIsRead) {
  auto bad = EncodeKobukiPacket(Data(1, 10, 20));
  bad[8] ^= 0x01;
  const auto good = EncodeKobukiPacket(Data(2, 11, 21));
  std::vector<std::uint8_t> stream = {0x00, 0xAA, 0x13};  // garbage with a false header start
  stream.insert(stream.end(), bad.begin(), bad.end());
  stream.insert(stream.end(), good.begin(), good.end());
  KobukiPacketDecoder decoder;
  std::vector<KobukiBasicSensorData> out;
  decoder.Push(stream.data(), stream.size(), &out);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].timestamp_ms, 2);
  EXPECT_EQ(decoder.stats().checksum_errors, 1);
  EXPECT_GE(decoder.stats().garbage_bytes, 3);
}

TEST(KobukiOdometryTest, TickDeltaHandlesWrapAround) {
  EXPECT_EQ(TickDelta(65530, 4), 10);
  EXPECT_EQ(TickDelta(4, 65530), -10);
  EXPECT_EQ(TickDelta(100, 100), 0);
}

TEST(KobukiOdometryTest, StraightDriveAcrossTheCounterWrapIntegratesDistance) {
  KobukiGeometry g;
  KobukiOdometry odometry(g);
  const double metres_per_tick = 2 * M_PI * g.wheel_radius_m / g.ticks_per_revolution;
  std::uint16_t ticks = 65000;
  EXPECT_FALSE(odometry.Update(0, Data(0, ticks, ticks)).has_value());
  std::optional<OdometrySample> last;
  for (int k = 1; k <= 100; ++k) {  // 100 packets of 20 ticks, 20 ms apart: wraps at 65536
    ticks = static_cast<std::uint16_t>(ticks + 20);
    last = odometry.Update(k * 20000000LL, Data(static_cast<std::uint16_t>(k * 20), ticks, ticks));
  }
  ASSERT_TRUE(last.has_value());
  EXPECT_NEAR(last->T_world_robot.x_m, 2000 * metres_per_tick, 1e-9);
  EXPECT_NEAR(last->T_world_robot.y_m, 0.0, 1e-12);
  EXPECT_NEAR(last->linear_velocity_mps, 20 * metres_per_tick / 0.02, 1e-6);
  EXPECT_EQ(odometry.jumps(), 0);
}

TEST(KobukiOdometryTest, TurnInPlaceRotatesByWheelTravelOverWheelbase) {
  KobukiGeometry g;
  KobukiOdometry odometry(g);
  const double metres_per_tick = 2 * M_PI * g.wheel_radius_m / g.ticks_per_revolution;
  odometry.Update(0, Data(0, 1000, 1000));
  const auto s = odometry.Update(20000000, Data(20, 990, 1010));
  ASSERT_TRUE(s.has_value());
  EXPECT_NEAR(s->T_world_robot.yaw_rad, 20 * metres_per_tick / g.wheelbase_m, 1e-12);
  EXPECT_NEAR(s->T_world_robot.x_m, 0.0, 1e-12);
}

TEST(KobukiOdometryTest, ImpossibleEncoderJumpIsCountedAndNotIntegrated) {
  KobukiGeometry g;
  KobukiOdometry odometry(g);
  odometry.Update(0, Data(0, 0, 0));
  const auto s = odometry.Update(20000000, Data(20, 20000, 20000));  // 5 m in 20 ms
  ASSERT_TRUE(s.has_value());
  EXPECT_EQ(odometry.jumps(), 1);
  EXPECT_EQ(s->T_world_robot.x_m, 0.0);
  // The next packet continues from the jumped counts without a second jump.
  const auto next = odometry.Update(40000000, Data(40, 20010, 20010));
  EXPECT_EQ(odometry.jumps(), 1);
  EXPECT_GT(next->T_world_robot.x_m, 0.0);
}

}  // namespace
}  // namespace uwbsar::live
