#include "drivers/dds/ros2_convert.h"

#include <cmath>

namespace uwbsar::dds {

TimestampNs StampToNs(const builtin_interfaces_msg_dds__Time_& stamp) {
  return static_cast<TimestampNs>(stamp.sec_) * 1000000000LL +
         static_cast<TimestampNs>(stamp.nanosec_);
}

builtin_interfaces_msg_dds__Time_ NsToStamp(TimestampNs t) {
  TimestampNs sec = t / 1000000000LL;
  TimestampNs nsec = t % 1000000000LL;
  if (nsec < 0) {
    nsec += 1000000000LL;
    --sec;
  }
  builtin_interfaces_msg_dds__Time_ stamp;
  stamp.sec_ = static_cast<std::int32_t>(sec);
  stamp.nanosec_ = static_cast<std::uint32_t>(nsec);
  return stamp;
}

double YawFromQuaternion(double x, double y, double z, double w) {
  return std::atan2(2.0 * (w * z + x * y), w * w + x * x - y * y - z * z);
}

geometry_msgs_msg_dds__Pose_ PoseToDds(const Pose2& pose) {
  geometry_msgs_msg_dds__Pose_ out;
  out.position_.x_ = pose.x_m;
  out.position_.y_ = pose.y_m;
  out.position_.z_ = 0.0;
  out.orientation_.x_ = 0.0;
  out.orientation_.y_ = 0.0;
  out.orientation_.z_ = std::sin(0.5 * pose.yaw_rad);
  out.orientation_.w_ = std::cos(0.5 * pose.yaw_rad);
  return out;
}

bool OdometryFromDds(const nav_msgs_msg_dds__Odometry_& msg, OdometrySample* out,
                     std::string* why) {
  const auto& p = msg.pose_.pose_.position_;
  const auto& q = msg.pose_.pose_.orientation_;
  const auto& v = msg.twist_.twist_;
  const double values[] = {p.x_, p.y_, q.x_, q.y_, q.z_, q.w_, v.linear_.x_, v.angular_.z_};
  for (const double value : values) {
    if (!std::isfinite(value)) {
      *why = "odometry pose or twist is not finite";
      return false;
    }
  }
  if (q.x_ == 0.0 && q.y_ == 0.0 && q.z_ == 0.0 && q.w_ == 0.0) {
    *why = "odometry orientation is the zero quaternion";
    return false;
  }
  out->stamp_ns = StampToNs(msg.header_.stamp_);
  out->T_world_robot = {p.x_, p.y_, YawFromQuaternion(q.x_, q.y_, q.z_, q.w_)};
  out->linear_velocity_mps = v.linear_.x_;
  out->angular_velocity_radps = v.angular_.z_;
  return true;
}

}  // namespace uwbsar::dds
