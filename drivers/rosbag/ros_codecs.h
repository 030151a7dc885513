// CDR decoders and encoders for the message types in ros_messages.h, plus their
// `ros2msg` definitions (what MCAP schema records and rosbag2 schema-4 tables hold).
// Decoders throw InputError("CDR ...") on malformed bytes; callers add the file and
// topic. Decoding into an existing struct reuses its vectors' capacity.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/types.h"
#include "drivers/rosbag/ros_messages.h"

namespace uwbsar::rosbag {

void DecodeCdr(const std::uint8_t* data, std::size_t size, Float32MultiArray* msg);
void DecodeCdr(const std::uint8_t* data, std::size_t size, Odometry* msg);
void DecodeCdr(const std::uint8_t* data, std::size_t size, LaserScan* msg);
void DecodeCdr(const std::uint8_t* data, std::size_t size, TfMessage* msg);

/// Each clears `out` and writes the full serialized message (with encapsulation header).
void EncodeCdr(const Float32MultiArray& msg, std::vector<std::uint8_t>* out);
void EncodeCdr(const Odometry& msg, std::vector<std::uint8_t>* out);
void EncodeCdr(const LaserScan& msg, std::vector<std::uint8_t>* out);
void EncodeCdr(const TfMessage& msg, std::vector<std::uint8_t>* out);
void EncodeCdr(const OccupancyGridMessage& msg, std::vector<std::uint8_t>* out);
void EncodeCdr(const PathMessage& msg, std::vector<std::uint8_t>* out);
void EncodeCdr(const ImageMessage& msg, std::vector<std::uint8_t>* out);
void EncodeCdr(const MarkerArray& msg, std::vector<std::uint8_t>* out);

/// The `ros2msg` text of a known type with its dependencies appended in the
/// rosbag2/MCAP convention ("=====...\nMSG: pkg/Type\n..."); empty if unknown.
std::string RosMessageDefinition(const std::string& type);

/// `stamp_ns` as a ROS 2 time (floor seconds, nanoseconds 0 .. 999999999). Throws
/// std::out_of_range outside core/stamp_range.h's range, which int32 seconds would wrap
/// (readers refuse such stamps first: this is a bug, never an input).
RosTime ToRosTime(TimestampNs stamp_ns);

/// Yaw of a unit quaternion about +z (rotation from the child to the parent frame).
double YawFromQuaternion(const Quaternion& q);
/// The quaternion of a rotation by `yaw_rad` about +z.
Quaternion QuaternionFromYaw(double yaw_rad);

}  // namespace uwbsar::rosbag
