#include "drivers/rosbag/ros_codecs.h"

#include <cmath>
#include <stdexcept>

#include "core/stamp_range.h"
#include "drivers/rosbag/cdr_reader.h"
#include "drivers/rosbag/cdr_writer.h"

namespace uwbsar::rosbag {
namespace {

void Read(CdrReader& r, RosHeader* h) {
  h->stamp.sec = r.Read<std::int32_t>();
  h->stamp.nanosec = r.Read<std::uint32_t>();
  h->frame_id = r.ReadString();
}

void Read(CdrReader& r, Vector3* v) {
  v->x = r.Read<double>();
  v->y = r.Read<double>();
  v->z = r.Read<double>();
}

void Read(CdrReader& r, Quaternion* q) {
  q->x = r.Read<double>();
  q->y = r.Read<double>();
  q->z = r.Read<double>();
  q->w = r.Read<double>();
}

void Write(CdrWriter& w, const RosHeader& h) {
  w.Write(h.stamp.sec);
  w.Write(h.stamp.nanosec);
  w.WriteString(h.frame_id);
}

void Write(CdrWriter& w, const Vector3& v) {
  w.Write(v.x);
  w.Write(v.y);
  w.Write(v.z);
}

void Write(CdrWriter& w, const Quaternion& q) {
  w.Write(q.x);
  w.Write(q.y);
  w.Write(q.z);
  w.Write(q.w);
}

void Write(CdrWriter& w, const RosPose& p) {
  Write(w, p.position);
  Write(w, p.orientation);
}

void Write(CdrWriter& w, const ColorRgba& c) {
  for (float v : {c.r, c.g, c.b, c.a}) w.Write(v);
}

void Write(CdrWriter& w, const Marker& m) {
  Write(w, m.header);
  w.WriteString(m.ns);
  w.Write(m.id);
  w.Write(m.type);
  w.Write(m.action);
  Write(w, m.pose);
  Write(w, m.scale);
  Write(w, m.color);
  w.Write(std::int32_t{0});   // lifetime.sec: forever
  w.Write(std::uint32_t{0});  // lifetime.nanosec
  w.Write(std::uint8_t{0});   // frame_locked
  w.WriteSequenceLength(m.points.size());
  for (const Vector3& p : m.points) Write(w, p);
  w.WriteSequenceLength(0);  // colors: all m.color
  w.WriteString("");         // texture_resource
  Write(w, RosHeader{});     // texture (sensor_msgs/CompressedImage): header, format, data
  w.WriteString("");
  w.WriteSequenceLength(0);
  w.WriteSequenceLength(0);  // uv_coordinates
  w.WriteString(m.text);
  w.WriteString("");         // mesh_resource
  w.WriteString("");         // mesh_file.filename
  w.WriteSequenceLength(0);  // mesh_file.data
  w.Write(std::uint8_t{0});  // mesh_use_embedded_materials
}

}  // namespace

void DecodeCdr(const std::uint8_t* data, std::size_t size, Float32MultiArray* msg) {
  CdrReader r(data, size);
  // Each dimension needs at least 12 bytes (string length, size, stride).
  msg->dim.resize(r.ReadSequenceLength(12));
  for (auto& d : msg->dim) {
    d.label = r.ReadString();
    d.size = r.Read<std::uint32_t>();
    d.stride = r.Read<std::uint32_t>();
  }
  msg->data_offset = r.Read<std::uint32_t>();
  r.ReadSequence(&msg->data);
  r.ExpectEnd();
}

void DecodeCdr(const std::uint8_t* data, std::size_t size, Odometry* msg) {
  CdrReader r(data, size);
  Read(r, &msg->header);
  msg->child_frame_id = r.ReadString();
  Read(r, &msg->position);
  Read(r, &msg->orientation);
  r.ReadArray(msg->pose_covariance.data(), msg->pose_covariance.size());
  Read(r, &msg->linear);
  Read(r, &msg->angular);
  r.ReadArray(msg->twist_covariance.data(), msg->twist_covariance.size());
  r.ExpectEnd();
}

void DecodeCdr(const std::uint8_t* data, std::size_t size, LaserScan* msg) {
  CdrReader r(data, size);
  Read(r, &msg->header);
  msg->angle_min = r.Read<float>();
  msg->angle_max = r.Read<float>();
  msg->angle_increment = r.Read<float>();
  msg->time_increment = r.Read<float>();
  msg->scan_time = r.Read<float>();
  msg->range_min = r.Read<float>();
  msg->range_max = r.Read<float>();
  r.ReadSequence(&msg->ranges);
  r.ReadSequence(&msg->intensities);
  r.ExpectEnd();
}

void DecodeCdr(const std::uint8_t* data, std::size_t size, TfMessage* msg) {
  CdrReader r(data, size);
  // Each transform needs at least 8 + 4 + 4 + 7 * 8 bytes.
  msg->transforms.resize(r.ReadSequenceLength(72));
  for (auto& t : msg->transforms) {
    Read(r, &t.header);
    t.child_frame_id = r.ReadString();
    Read(r, &t.translation);
    Read(r, &t.rotation);
  }
  r.ExpectEnd();
}

void EncodeCdr(const Float32MultiArray& msg, std::vector<std::uint8_t>* out) {
  CdrWriter w(out);
  w.WriteSequenceLength(msg.dim.size());
  for (const auto& d : msg.dim) {
    w.WriteString(d.label);
    w.Write(d.size);
    w.Write(d.stride);
  }
  w.Write(msg.data_offset);
  w.WriteSequence(msg.data);
}

void EncodeCdr(const Odometry& msg, std::vector<std::uint8_t>* out) {
  CdrWriter w(out);
  Write(w, msg.header);
  w.WriteString(msg.child_frame_id);
  Write(w, msg.position);
  Write(w, msg.orientation);
  w.WriteArray(msg.pose_covariance.data(), msg.pose_covariance.size());
  Write(w, msg.linear);
  Write(w, msg.angular);
  w.WriteArray(msg.twist_covariance.data(), msg.twist_covariance.size());
}

void EncodeCdr(const LaserScan& msg, std::vector<std::uint8_t>* out) {
  CdrWriter w(out);
  Write(w, msg.header);
  for (float v : {msg.angle_min, msg.angle_max, msg.angle_increment, msg.time_increment,
                  msg.scan_time, msg.range_min, msg.range_max}) {
    w.Write(v);
  }
  w.WriteSequence(msg.ranges);
  w.WriteSequence(msg.intensities);
}

void EncodeCdr(const TfMessage& msg, std::vector<std::uint8_t>* out) {
  CdrWriter w(out);
  w.WriteSequenceLength(msg.transforms.size());
  for (const auto& t : msg.transforms) {
    Write(w, t.header);
    w.WriteString(t.child_frame_id);
    Write(w, t.translation);
    Write(w, t.rotation);
  }
}

void EncodeCdr(const OccupancyGridMessage& msg, std::vector<std::uint8_t>* out) {
  CdrWriter w(out);
  Write(w, msg.header);
  w.Write(msg.map_load_time.sec);
  w.Write(msg.map_load_time.nanosec);
  w.Write(msg.resolution);
  w.Write(msg.width);
  w.Write(msg.height);
  Write(w, msg.origin);
  w.WriteSequence(msg.data);
}

void EncodeCdr(const PathMessage& msg, std::vector<std::uint8_t>* out) {
  CdrWriter w(out);
  Write(w, msg.header);
  w.WriteSequenceLength(msg.poses.size());
  for (const PoseStamped& p : msg.poses) {
    Write(w, p.header);
    Write(w, p.pose);
  }
}

void EncodeCdr(const ImageMessage& msg, std::vector<std::uint8_t>* out) {
  CdrWriter w(out);
  Write(w, msg.header);
  w.Write(msg.height);
  w.Write(msg.width);
  w.WriteString(msg.encoding);
  w.Write(msg.is_bigendian);
  w.Write(msg.step);
  w.WriteSequence(msg.data);
}

void EncodeCdr(const MarkerArray& msg, std::vector<std::uint8_t>* out) {
  CdrWriter w(out);
  w.WriteSequenceLength(msg.markers.size());
  for (const Marker& m : msg.markers) Write(w, m);
}

RosTime ToRosTime(TimestampNs stamp_ns) {
  if (!IsOutputStamp(stamp_ns)) throw std::out_of_range(StampOutsideOutputRange(stamp_ns));
  return {static_cast<std::int32_t>(stamp_ns / 1000000000),
          static_cast<std::uint32_t>(stamp_ns % 1000000000)};
}

double YawFromQuaternion(const Quaternion& q) {
  return std::atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z));
}

Quaternion QuaternionFromYaw(double yaw_rad) {
  Quaternion q;
  q.z = std::sin(0.5 * yaw_rad);
  q.w = std::cos(0.5 * yaw_rad);
  return q;
}

}  // namespace uwbsar::rosbag
