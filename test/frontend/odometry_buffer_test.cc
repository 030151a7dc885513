// OdometryBuffer: interpolation at scan stamps, the lookup's out-of-range answers and
// the sanity rules of its header (order, non-finite, outliers held then dropped or
// confirmed, jumps re-anchored).
#include "frontend/odometry_buffer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace uwbsar {
namespace {

constexpr TimestampNs kMs = 1000000;

OdometrySample Sample(TimestampNs stamp_ns, double x_m, double y_m = 0.0, double yaw_rad = 0.0) {
  OdometrySample s;
  s.stamp_ns = stamp_ns;
  s.T_world_robot = {x_m, y_m, yaw_rad};
  return s;
}

TEST(OdometryBufferTest, LookupInterpolatesPoseAndPathBetweenBracketingSamples) {
  OdometryBuffer buffer{GatingConfig{}};
  buffer.Add(Sample(100 * kMs, 0.0, 0.0, 0.0));
  buffer.Add(Sample(200 * kMs, 0.3, 0.4, 0.2));  // 0.5 m step at 5 m/s
  OdometryEntry e;
  ASSERT_EQ(buffer.Lookup(125 * kMs, &e), OdometryBuffer::LookupResult::kOk);
  EXPECT_EQ(e.stamp_ns, 125 * kMs);
  EXPECT_NEAR(e.T_world_robot.x_m, 0.075, 1e-12);
  EXPECT_NEAR(e.T_world_robot.y_m, 0.1, 1e-12);
  EXPECT_NEAR(e.T_world_robot.yaw_rad, 0.05, 1e-12);
  EXPECT_NEAR(e.path_m, 0.125, 1e-12);
}

TEST(OdometryBufferTest, LookupAtASampleStampReturnsThatSample) {
  OdometryBuffer buffer{GatingConfig{}};
  buffer.Add(Sample(100 * kMs, 0.0));
  buffer.Add(Sample(200 * kMs, 0.2));
  buffer.Add(Sample(300 * kMs, 0.5));
  OdometryEntry e;
  ASSERT_EQ(buffer.Lookup(200 * kMs, &e), OdometryBuffer::LookupResult::kOk);
  EXPECT_DOUBLE_EQ(e.T_world_robot.x_m, 0.2);
  EXPECT_DOUBLE_EQ(e.path_m, 0.2);
  ASSERT_EQ(buffer.Lookup(100 * kMs, &e), OdometryBuffer::LookupResult::kOk);
  EXPECT_DOUBLE_EQ(e.path_m, 0.0);
  ASSERT_EQ(buffer.Lookup(300 * kMs, &e), OdometryBuffer::LookupResult::kOk);
  EXPECT_DOUBLE_EQ(e.path_m, 0.5);
}

TEST(OdometryBufferTest, LookupOutsideTheSamplesSaysWhichSide) {
  OdometryBuffer buffer{GatingConfig{}};
  OdometryEntry e;
  EXPECT_EQ(buffer.Lookup(100 * kMs, &e), OdometryBuffer::LookupResult::kBeforeFirst);
  buffer.Add(Sample(100 * kMs, 0.0));
  buffer.Add(Sample(200 * kMs, 0.1));
  EXPECT_EQ(buffer.Lookup(100 * kMs - 1, &e), OdometryBuffer::LookupResult::kBeforeFirst);
  EXPECT_EQ(buffer.Lookup(200 * kMs + 1, &e), OdometryBuffer::LookupResult::kAfterLast);
}

TEST(OdometryBufferTest, LookupBetweenSamplesFartherApartThanMaxGapIsAGap) {
  GatingConfig config;
  config.max_odom_gap_s = 0.5;
  OdometryBuffer buffer{config};
  buffer.Add(Sample(0, 0.0));
  buffer.Add(Sample(600 * kMs, 0.1));
  buffer.Add(Sample(1000 * kMs, 0.2));
  OdometryEntry e;
  EXPECT_EQ(buffer.Lookup(300 * kMs, &e), OdometryBuffer::LookupResult::kGap);
  EXPECT_EQ(buffer.Lookup(800 * kMs, &e), OdometryBuffer::LookupResult::kOk);
}

TEST(OdometryBufferTest, SamplesNotAfterTheNewestAreDroppedAsOutOfOrder) {
  OdometryBuffer buffer{GatingConfig{}};
  buffer.Add(Sample(100 * kMs, 0.0));
  buffer.Add(Sample(200 * kMs, 0.1));
  EXPECT_EQ(buffer.Add(Sample(200 * kMs, 0.15)).result, OdometryBuffer::AddResult::kOutOfOrder);
  EXPECT_EQ(buffer.Add(Sample(150 * kMs, 0.05)).result, OdometryBuffer::AddResult::kOutOfOrder);
  EXPECT_EQ(buffer.entries().size(), 2u);
  EXPECT_EQ(buffer.latest_stamp_ns(), 200 * kMs);
}

TEST(OdometryBufferTest, NonFiniteOrOffEarthPosesAreDropped) {
  OdometryBuffer buffer{GatingConfig{}};
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(buffer.Add(Sample(100 * kMs, nan)).result, OdometryBuffer::AddResult::kNonFinite);
  EXPECT_EQ(buffer.Add(Sample(100 * kMs, 0.0, inf)).result, OdometryBuffer::AddResult::kNonFinite);
  EXPECT_EQ(buffer.Add(Sample(100 * kMs, 0.0, 0.0, nan)).result,
            OdometryBuffer::AddResult::kNonFinite);
  EXPECT_EQ(buffer.Add(Sample(100 * kMs, 2.0 * kMaxOdomCoordinateM)).result,
            OdometryBuffer::AddResult::kNonFinite);
  EXPECT_TRUE(buffer.empty());
  EXPECT_EQ(buffer.Add(Sample(100 * kMs, 0.0)).result, OdometryBuffer::AddResult::kAccepted);
}

TEST(OdometryBufferTest, ASingleImpossibleStepIsHeldThenDroppedAsAnOutlier) {
  OdometryBuffer buffer{GatingConfig{}};
  buffer.Add(Sample(100 * kMs, 0.0));
  buffer.Add(Sample(200 * kMs, 0.1));
  const auto held = buffer.Add(Sample(300 * kMs, 1e20));
  EXPECT_EQ(held.result, OdometryBuffer::AddResult::kNonFinite);  // beyond kMaxOdomCoordinateM
  const auto far = buffer.Add(Sample(300 * kMs, 50.0));           // 500 m/s
  EXPECT_EQ(far.result, OdometryBuffer::AddResult::kHeld);
  EXPECT_EQ(buffer.entries().size(), 2u);
  const auto next = buffer.Add(Sample(400 * kMs, 0.2));  // agrees with the last accepted
  EXPECT_EQ(next.result, OdometryBuffer::AddResult::kAccepted);
  EXPECT_TRUE(next.outlier_dropped);
  EXPECT_EQ(next.appended, 1);
  ASSERT_EQ(buffer.entries().size(), 3u);
  EXPECT_DOUBLE_EQ(buffer.entries().back().T_world_robot.x_m, 0.2);
  EXPECT_NEAR(buffer.entries().back().path_m, 0.2, 1e-12);
}

TEST(OdometryBufferTest, AnImpossibleStepConfirmedByTheNextIsKeptAsAReanchoredJump) {
  OdometryBuffer buffer{GatingConfig{}};
  buffer.Add(Sample(100 * kMs, 0.0));
  buffer.Add(Sample(200 * kMs, 0.1));
  EXPECT_EQ(buffer.Add(Sample(300 * kMs, 50.0)).result, OdometryBuffer::AddResult::kHeld);
  const auto confirm = buffer.Add(Sample(400 * kMs, 50.1));  // agrees with the held one
  EXPECT_EQ(confirm.result, OdometryBuffer::AddResult::kAccepted);
  EXPECT_EQ(confirm.appended, 2);
  EXPECT_EQ(confirm.jumps, 1);
  EXPECT_FALSE(confirm.outlier_dropped);
  ASSERT_EQ(buffer.entries().size(), 4u);
  // The jump is zero motion: the held sample lands where the robot was, and the
  // next continues from there by its own 0.1 m step.
  EXPECT_NEAR(buffer.entries()[2].T_world_robot.x_m, 0.1, 1e-9);
  EXPECT_NEAR(buffer.entries()[2].path_m, 0.1, 1e-9);
  EXPECT_NEAR(buffer.entries()[3].T_world_robot.x_m, 0.2, 1e-9);
  EXPECT_NEAR(buffer.entries()[3].path_m, 0.2, 1e-9);
}

TEST(OdometryBufferTest, APlausibleStepLongerThanMaxJumpIsReanchored) {
  GatingConfig config;
  config.max_odom_jump_m = 0.5;
  OdometryBuffer buffer{config};
  buffer.Add(Sample(0, 1.0, 2.0, 0.0));
  // 0.8 m in 1 s: a possible speed, but longer than max_odom_jump_m.
  const auto jump = buffer.Add(Sample(1000 * kMs, 1.8, 2.0, 0.0));
  EXPECT_EQ(jump.result, OdometryBuffer::AddResult::kAccepted);
  EXPECT_EQ(jump.jumps, 1);
  EXPECT_NEAR(buffer.entries().back().T_world_robot.x_m, 1.0, 1e-9);
  EXPECT_NEAR(buffer.entries().back().path_m, 0.0, 1e-9);
  // Later steps move on from the re-anchored pose.
  buffer.Add(Sample(1100 * kMs, 1.9, 2.0, 0.0));
  EXPECT_NEAR(buffer.entries().back().T_world_robot.x_m, 1.1, 1e-9);
  EXPECT_NEAR(buffer.entries().back().path_m, 0.1, 1e-9);
}

TEST(OdometryBufferTest, ATurnFasterThanTheMaxTurnRateIsHeld) {
  GatingConfig config;
  config.max_odom_turn_rate_radps = 1.0;
  OdometryBuffer buffer{config};
  buffer.Add(Sample(0, 0.0));
  EXPECT_EQ(buffer.Add(Sample(100 * kMs, 0.0, 0.0, 0.5)).result,
            OdometryBuffer::AddResult::kHeld);  // 5 rad/s
  EXPECT_EQ(buffer.Add(Sample(200 * kMs, 0.0, 0.0, 0.1)).result,
            OdometryBuffer::AddResult::kAccepted);  // 0.5 rad/s from the first
}

TEST(OdometryBufferTest, DropHeldReportsWhetherASampleWasWaiting) {
  OdometryBuffer buffer{GatingConfig{}};
  buffer.Add(Sample(100 * kMs, 0.0));
  EXPECT_FALSE(buffer.DropHeld());
  buffer.Add(Sample(200 * kMs, 50.0));
  EXPECT_TRUE(buffer.DropHeld());
  EXPECT_FALSE(buffer.DropHeld());
  EXPECT_EQ(buffer.entries().size(), 1u);
}

TEST(OdometryBufferTest, TrimBeforeKeepsOneSampleBeforeTheStampForInterpolation) {
  OdometryBuffer buffer{GatingConfig{}};
  for (int i = 0; i < 5; ++i) buffer.Add(Sample(i * 100 * kMs, 0.01 * i));
  buffer.TrimBefore(250 * kMs);
  ASSERT_EQ(buffer.entries().size(), 3u);
  EXPECT_EQ(buffer.entries().front().stamp_ns, 200 * kMs);
  OdometryEntry e;
  EXPECT_EQ(buffer.Lookup(250 * kMs, &e), OdometryBuffer::LookupResult::kOk);
  EXPECT_EQ(buffer.Lookup(150 * kMs, &e), OdometryBuffer::LookupResult::kBeforeFirst);
}

}  // namespace
}  // namespace uwbsar
