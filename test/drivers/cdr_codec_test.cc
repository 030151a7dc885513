// CDR (XCDR1 little-endian) decoders and encoders of the four message types.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "core/errors.h"
#include "drivers/rosbag/cdr_reader.h"
#include "drivers/rosbag/cdr_writer.h"
#include "drivers/rosbag/ros_codecs.h"

namespace uwbsar::rosbag {
namespace {

Odometry SampleOdometry() {
  Odometry m;
  m.header.stamp = {12, 345};
  m.header.frame_id = "odom";
  m.child_frame_id = "base_link";
  m.position = {1.5, -2.25, 0.0};
  m.orientation = QuaternionFromYaw(0.75);
  for (std::size_t i = 0; i < 36; ++i) m.pose_covariance[i] = 0.5 * static_cast<double>(i);
  m.linear = {0.3, 0, 0};
  m.angular = {0, 0, -0.2};
  m.twist_covariance[35] = 9.0;
  return m;
}

TEST(CdrCodecTest, OdometryLayoutMatchesTheReference) {
  std::vector<std::uint8_t> bytes;
  EncodeCdr(SampleOdometry(), &bytes);
  // With frames odom/base_link a nav_msgs/Odometry is 724 bytes and position.x
  // sits at payload offset 40 (after the 4-byte encapsulation header).
  ASSERT_EQ(bytes.size(), 724u);
  EXPECT_EQ(bytes[0], 0x00);
  EXPECT_EQ(bytes[1], 0x01);
  double x = 0;
  std::memcpy(&x, bytes.data() + 4 + 40, 8);
  EXPECT_EQ(x, 1.5);
}

TEST(CdrCodecTest, OdometryRoundTripsExactly) {
  const Odometry in = SampleOdometry();
  std::vector<std::uint8_t> bytes;
  EncodeCdr(in, &bytes);
  Odometry out;
  DecodeCdr(bytes.data(), bytes.size(), &out);
  EXPECT_EQ(out.header.stamp.sec, 12);
  EXPECT_EQ(out.header.stamp.nanosec, 345u);
  EXPECT_EQ(out.header.frame_id, "odom");
  EXPECT_EQ(out.child_frame_id, "base_link");
  EXPECT_EQ(out.position.y, -2.25);
  EXPECT_EQ(out.orientation.z, in.orientation.z);
  EXPECT_EQ(out.pose_covariance, in.pose_covariance);
  EXPECT_EQ(out.twist_covariance, in.twist_covariance);
  EXPECT_EQ(out.angular.z, -0.2);
  EXPECT_NEAR(YawFromQuaternion(out.orientation), 0.75, 1e-15);
}

TEST(CdrCodecTest, Float32MultiArrayRoundTripsWithLayout) {
  Float32MultiArray in;
  in.dim = {{"range", 3, 3}, {"x", 1, 1}};
  in.data_offset = 2;
  in.data = {1.0f, -0.0f, 3.4e38f, 1e-45f};
  std::vector<std::uint8_t> bytes;
  EncodeCdr(in, &bytes);
  Float32MultiArray out;
  DecodeCdr(bytes.data(), bytes.size(), &out);
  ASSERT_EQ(out.dim.size(), 2u);
  EXPECT_EQ(out.dim[0].label, "range");
  EXPECT_EQ(out.dim[1].stride, 1u);
  EXPECT_EQ(out.data_offset, 2u);
  ASSERT_EQ(out.data.size(), 4u);
  EXPECT_EQ(std::memcmp(out.data.data(), in.data.data(), 16), 0);  // bit for bit, -0 included
}

TEST(CdrCodecTest, LaserScanAndTfRoundTrip) {
  LaserScan scan;
  scan.header.frame_id = "laser";
  scan.angle_increment = 0.01f;
  scan.ranges = {1, 2, 3};
  std::vector<std::uint8_t> bytes;
  EncodeCdr(scan, &bytes);
  LaserScan scan_out;
  DecodeCdr(bytes.data(), bytes.size(), &scan_out);
  EXPECT_EQ(scan_out.ranges, scan.ranges);
  EXPECT_TRUE(scan_out.intensities.empty());
  EXPECT_EQ(scan_out.angle_increment, 0.01f);

  TfMessage tf;
  tf.transforms.resize(2);
  tf.transforms[1].child_frame_id = "radar";
  tf.transforms[1].translation.y = 0.18;
  EncodeCdr(tf, &bytes);
  TfMessage tf_out;
  DecodeCdr(bytes.data(), bytes.size(), &tf_out);
  ASSERT_EQ(tf_out.transforms.size(), 2u);
  EXPECT_EQ(tf_out.transforms[1].child_frame_id, "radar");
  EXPECT_EQ(tf_out.transforms[1].translation.y, 0.18);
}

TEST(CdrCodecTest, AlignmentIsRelativeToThePayloadStart) {
  std::vector<std::uint8_t> bytes;
  CdrWriter w(&bytes);
  w.Write<std::uint8_t>(7);
  w.Write<double>(2.5);  // 7 padding bytes: offset 8 of the payload, 12 of the buffer
  ASSERT_EQ(bytes.size(), 4u + 16u);
  CdrReader r(bytes.data(), bytes.size());
  EXPECT_EQ(r.Read<std::uint8_t>(), 7);
  EXPECT_EQ(r.Read<double>(), 2.5);
  EXPECT_EQ(r.Offset(), 16u);
}

void ExpectDecodeError(const std::vector<std::uint8_t>& bytes, const std::string& fragment) {
  Odometry out;
  try {
    DecodeCdr(bytes.data(), bytes.size(), &out);
    FAIL() << "no error, expected: " << fragment;
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

TEST(CdrCodecTest, BigEndianEncapsulationIsRejectedClearly) {
  std::vector<std::uint8_t> bytes;
  EncodeCdr(SampleOdometry(), &bytes);
  bytes[1] = 0x00;
  ExpectDecodeError(bytes, "big-endian CDR");
  bytes[1] = 0x07;
  ExpectDecodeError(bytes, "XCDR2");
}

TEST(CdrCodecTest, TruncatedPayloadIsAnOverrunNotACrash) {
  std::vector<std::uint8_t> bytes;
  EncodeCdr(SampleOdometry(), &bytes);
  for (std::size_t n : {0, 3, 4, 9, 20, 100, 723}) {
    std::vector<std::uint8_t> cut(bytes.begin(), bytes.begin() + static_cast<long>(n));
    Odometry out;
    EXPECT_THROW(DecodeCdr(cut.data(), cut.size(), &out), InputError) << n;
  }
  ExpectDecodeError({bytes.begin(), bytes.begin() + 100}, "overruns");
}

TEST(CdrCodecTest, HugeLengthsAreRejectedBeforeAllocating) {
  std::vector<std::uint8_t> bytes;
  EncodeCdr(SampleOdometry(), &bytes);
  const std::uint32_t huge = 0xFFFFFFF0u;
  std::memcpy(bytes.data() + 4 + 8, &huge, 4);  // frame_id length
  ExpectDecodeError(bytes, "string of 4294967280 bytes at payload offset 12 overruns");

  Float32MultiArray f;
  f.data = {1, 2, 3};
  EncodeCdr(f, &bytes);
  std::memcpy(bytes.data() + 4 + 8, &huge, 4);  // data count (after dim count and offset)
  Float32MultiArray out;
  EXPECT_THROW(DecodeCdr(bytes.data(), bytes.size(), &out), InputError);
}

TEST(CdrCodecTest, StringWithoutNulIsRejected) {
  std::vector<std::uint8_t> bytes;
  EncodeCdr(SampleOdometry(), &bytes);
  bytes[4 + 12 + 4] = 'x';  // the NUL after "odom"
  ExpectDecodeError(bytes, "not NUL-terminated");
}

TEST(CdrCodecTest, WrongTypeLeavesBytesAndIsRejected) {
  std::vector<std::uint8_t> bytes;
  LaserScan scan;
  scan.ranges.assign(200, 1.0f);
  EncodeCdr(scan, &bytes);
  Float32MultiArray out;  // a LaserScan decoded as a Float32MultiArray
  EXPECT_THROW(DecodeCdr(bytes.data(), bytes.size(), &out), InputError);
}

TEST(CdrCodecTest, MessageDefinitionsListDependencies) {
  const std::string def = RosMessageDefinition("nav_msgs/msg/Odometry");
  EXPECT_EQ(def.rfind("std_msgs/Header header\n", 0), 0u);
  EXPECT_NE(def.find("MSG: geometry_msgs/Quaternion\nfloat64 x"), std::string::npos);
  EXPECT_TRUE(RosMessageDefinition("foo_msgs/msg/Bar").empty());
}

}  // namespace
}  // namespace uwbsar::rosbag
