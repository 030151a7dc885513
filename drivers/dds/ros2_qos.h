// ROS 2 naming and QoS as rmw_cyclonedds puts them on the wire: ROS topic "/odom"
// is DDS topic "rt/odom"; readers and writers use classic CDR (XCDR1) only, which is
// what every ROS 2 node offers and expects.
#pragma once

#include <dds/dds.h>

#include <string>

namespace uwbsar::dds {

/// The DDS topic of a ROS 2 topic name: "rt" + the absolute name ("odom" -> "rt/odom").
/// Throws InputError for an empty name or one with characters ROS 2 does not allow.
std::string RosTopicToDds(const std::string& ros_topic);
/// The ROS 2 name of a DDS topic ("rt/odom" -> "/odom"); "" for a non-ROS topic.
std::string DdsTopicToRos(const std::string& dds_topic);

/// Owns a dds_qos_t.
class Qos {
 public:
  Qos() : qos_(dds_create_qos()) {}
  ~Qos() { dds_delete_qos(qos_); }
  Qos(const Qos&) = delete;
  Qos& operator=(const Qos&) = delete;
  const dds_qos_t* get() const { return qos_; }
  dds_qos_t* get() { return qos_; }

 private:
  dds_qos_t* qos_;
};

enum class Durability { kVolatile, kTransientLocal };

/// XCDR1, keep-last `depth`, reliable (or best effort) and the given durability.
/// `reliability` is "reliable" or "best_effort"; anything else throws InputError
/// naming dds.reliability.
void SetRos2Qos(dds_qos_t* qos, const std::string& reliability, int depth, Durability durability);

}  // namespace uwbsar::dds
